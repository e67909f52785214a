/**
 * Image sizes read from the file header, before any decoder runs: decoders allocate from the sizes
 * a header claims (a 69-byte PNG can claim 2^31 x 2^31 texels), so the loaders check them against
 * the resource policy first. Each reader follows its format's specification for the first bytes:
 * PNG (ISO/IEC 15948, 11.2.2 IHDR), JPEG (ITU-T T.81, B.2.2 frame header), WebP (RFC 9649: VP8,
 * VP8L and VP8X chunks), KTX 2.0 (KTX File Format 2.0, section 3 header), AVIF (ISO/IEC 23008-12
 * image spatial extents `ispe`, inside meta/iprp/ipco).
 */
import { refuse, type DecodeBudget, type ResourceSite } from './resource-policy.ts';

export type HeaderFormat = 'png' | 'jpeg' | 'webp' | 'ktx2' | 'avif';

export interface ImageHeader {
  format: HeaderFormat;
  width: number;
  height: number;
  /** Array layers x cube faces (KTX2), else 1. */
  layers: number;
  /** Bytes a decoder and its RGBA8 result hold per texel (an upper estimate, for the budget). */
  bytesPerTexel: number;
}

export type ImageHeaderResult = ImageHeader | { format: HeaderFormat; error: string };

function ascii(b: Uint8Array, at: number, text: string): boolean {
  for (let i = 0; i < text.length; i++) if (b[at + i] !== text.charCodeAt(i)) return false;
  return true;
}

const be32 = (b: Uint8Array, at: number): number => ((b[at]! << 24) >>> 0) + (b[at + 1]! << 16) + (b[at + 2]! << 8) + b[at + 3]!;
const le32 = (b: Uint8Array, at: number): number => (b[at]! | (b[at + 1]! << 8) | (b[at + 2]! << 16)) + b[at + 3]! * 2 ** 24;
const le16 = (b: Uint8Array, at: number): number => b[at]! | (b[at + 1]! << 8);
const le24 = (b: Uint8Array, at: number): number => b[at]! | (b[at + 1]! << 8) | (b[at + 2]! << 16);

/** The format by signature, or undefined when the bytes are none of those read here. */
export function sniffHeaderFormat(b: Uint8Array): HeaderFormat | undefined {
  if (b.length >= 8 && b[0] === 0x89 && ascii(b, 1, 'PNG\r\n\x1a\n')) return 'png';
  if (b.length >= 3 && b[0] === 0xff && b[1] === 0xd8 && b[2] === 0xff) return 'jpeg';
  if (b.length >= 12 && ascii(b, 0, 'RIFF') && ascii(b, 8, 'WEBP')) return 'webp';
  if (b.length >= 12 && b[0] === 0xab && ascii(b, 1, 'KTX 20') && b[7] === 0xbb) return 'ktx2';
  if (b.length >= 12 && ascii(b, 4, 'ftyp') && (ascii(b, 8, 'avif') || ascii(b, 8, 'avis'))) return 'avif';
  return undefined;
}

const PNG_CHANNELS: Readonly<Record<number, number>> = { 0: 1, 2: 3, 3: 1, 4: 2, 6: 4 };

function png(b: Uint8Array): ImageHeaderResult {
  if (b.length < 26 || be32(b, 8) !== 13 || !ascii(b, 12, 'IHDR')) return { format: 'png', error: 'the PNG does not start with a complete IHDR chunk' };
  const depth = b[24]!;
  const channels = PNG_CHANNELS[b[25]!];
  if (channels === undefined || ![1, 2, 4, 8, 16].includes(depth)) return { format: 'png', error: `the PNG IHDR has colour type ${b[25]} with bit depth ${depth}` };
  // Inflated scanlines and unpacked samples, a palette expansion, and the RGBA8 result.
  const sample = Math.max(1, depth / 8);
  return { format: 'png', width: be32(b, 16), height: be32(b, 20), layers: 1, bytesPerTexel: 2 * channels * sample + 8 };
}

function jpeg(b: Uint8Array): ImageHeaderResult {
  let p = 2;
  while (p + 4 <= b.length) {
    if (b[p] !== 0xff) return { format: 'jpeg', error: `expected a JPEG marker at byte ${p}` };
    const marker = b[p + 1]!;
    if (marker === 0xff) {
      p++; // fill byte
      continue;
    }
    if (marker === 0x01 || (marker >= 0xd0 && marker <= 0xd8)) {
      p += 2; // markers without a segment
      continue;
    }
    if (marker === 0xd9 || marker === 0xda) break;
    const length = (b[p + 2]! << 8) | b[p + 3]!;
    if (length < 2) return { format: 'jpeg', error: `JPEG segment at byte ${p} has length ${length}` };
    // SOF0..SOF15 are frame headers, except DHT (C4), JPG (C8) and DAC (CC).
    if (marker >= 0xc0 && marker <= 0xcf && marker !== 0xc4 && marker !== 0xc8 && marker !== 0xcc) {
      if (p + 10 > b.length || length < 8) return { format: 'jpeg', error: 'the JPEG frame header is truncated' };
      const height = (b[p + 5]! << 8) | b[p + 6]!;
      const width = (b[p + 7]! << 8) | b[p + 8]!;
      const components = b[p + 9]!;
      return { format: 'jpeg', width, height, layers: 1, bytesPerTexel: 4 + 2 * Math.max(1, components) };
    }
    p += 2 + length;
  }
  return { format: 'jpeg', error: 'the JPEG has no frame header (SOF) before its scan data' };
}

function webp(b: Uint8Array): ImageHeaderResult {
  if (b.length < 30) return { format: 'webp', error: 'the WebP header is truncated' };
  const data = 20;
  const header = (width: number, height: number): ImageHeader => ({ format: 'webp', width, height, layers: 1, bytesPerTexel: 8 });
  if (ascii(b, 12, 'VP8 ')) {
    if (b[data + 3] !== 0x9d || b[data + 4] !== 0x01 || b[data + 5] !== 0x2a) return { format: 'webp', error: 'the VP8 frame has no start code' };
    return header(le16(b, data + 6) & 0x3fff, le16(b, data + 8) & 0x3fff);
  }
  if (ascii(b, 12, 'VP8L')) {
    if (b[data] !== 0x2f) return { format: 'webp', error: 'the VP8L stream has no signature' };
    const bits = le32(b, data + 1);
    return header((bits & 0x3fff) + 1, (Math.floor(bits / 2 ** 14) & 0x3fff) + 1);
  }
  if (ascii(b, 12, 'VP8X')) return header(1 + le24(b, data + 4), 1 + le24(b, data + 7));
  return { format: 'webp', error: 'the WebP has no VP8, VP8L or VP8X chunk first' };
}

function ktx2(b: Uint8Array): ImageHeaderResult {
  if (b.length < 80) return { format: 'ktx2', error: 'the KTX2 container does not parse (its 80-byte header is truncated)' };
  const width = le32(b, 20);
  const height = Math.max(1, le32(b, 24));
  const depth = Math.max(1, le32(b, 28));
  const layers = Math.max(1, le32(b, 32)) * Math.max(1, le32(b, 36)) * depth;
  // Transcoded RGBA8 with its mip chain (4/3), plus the transcoder's own copy.
  return { format: 'ktx2', width, height, layers, bytesPerTexel: 12 };
}

/** Largest `ispe` extent in the file's meta box (the full image; grid tiles are smaller). */
function avif(b: Uint8Array): ImageHeaderResult {
  let width = 0;
  let height = 0;
  const walk = (start: number, end: number, depth: number): void => {
    let p = start;
    while (p + 8 <= end && depth < 6) {
      let size = be32(b, p);
      const type = String.fromCharCode(b[p + 4]!, b[p + 5]!, b[p + 6]!, b[p + 7]!);
      let header = 8;
      if (size === 1) {
        if (p + 16 > end) return;
        size = be32(b, p + 8) * 2 ** 32 + be32(b, p + 12);
        header = 16;
      } else if (size === 0) {
        size = end - p;
      }
      if (size < header || p + size > end) return;
      if (type === 'meta') walk(p + header + 4, p + size, depth + 1);
      else if (type === 'iprp' || type === 'ipco') walk(p + header, p + size, depth + 1);
      else if (type === 'ispe' && size >= header + 12) {
        width = Math.max(width, be32(b, p + header + 4));
        height = Math.max(height, be32(b, p + header + 8));
      }
      p += size;
    }
  };
  walk(0, b.length, 0);
  if (width === 0 || height === 0) return { format: 'avif', error: 'the AVIF has no image spatial extents (ispe) property' };
  return { format: 'avif', width, height, layers: 1, bytesPerTexel: 12 };
}

/** The header of PNG, JPEG, WebP, KTX2 or AVIF bytes; undefined for other formats. */
export function readImageHeader(bytes: Uint8Array): ImageHeaderResult | undefined {
  switch (sniffHeaderFormat(bytes)) {
    case 'png':
      return png(bytes);
    case 'jpeg':
      return jpeg(bytes);
    case 'webp':
      return webp(bytes);
    case 'ktx2':
      return ktx2(bytes);
    case 'avif':
      return avif(bytes);
    default:
      return undefined;
  }
}

/**
 * Refuses (at `site`) an image whose header is unreadable or claims an empty size or a side over
 * `maxImageDimension`, and charges its decoded bytes to `budget` when one is given. Returns the
 * header, or undefined for bytes of another format (the decoder reports those).
 */
export function checkImageHeader(bytes: Uint8Array, site: ResourceSite, limits: { maxImageDimension: number }, budget?: DecodeBudget): ImageHeader | undefined {
  const header = readImageHeader(bytes);
  if (header === undefined) return undefined;
  const name = header.format.toUpperCase();
  if ('error' in header) refuse(site, `the ${name} image does not decode: ${header.error}`);
  const { width, height } = header;
  if (width < 1 || height < 1) refuse(site, `${name} image: the header claims ${width} x ${height} texels`);
  if (width > limits.maxImageDimension || height > limits.maxImageDimension) {
    refuse(site, `${name} image: ${width} x ${height} texels exceed the largest side of ${limits.maxImageDimension} (resourcePolicy.maxImageDimension)`);
  }
  budget?.charge(width * height * header.layers * header.bytesPerTexel, site, `decoding the ${width} x ${height} ${name} image`);
  return header;
}
