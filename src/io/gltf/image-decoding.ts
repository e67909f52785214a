/**
 * Encoded image bytes -> RGBA8, top row first (WavefrontImageInput). The format is sniffed from the
 * signature, not trusted from mimeType. Node decodes with pure-JS/wasm packages (fast-png, jpeg-js,
 * webp-wasm, @jsquash/avif, all loaded on first use); browsers with createImageBitmap and
 * OffscreenCanvas use the platform decoders instead (feature-detected; a 2D canvas stores
 * premultiplied alpha, so colours of nearly transparent texels lose precision there). KTX2 is
 * decoded the same way everywhere (codecs/ktx2.ts: Basis Universal transcoder, loaded on first use).
 */
import type { WavefrontImageInput } from '../../scene/types.ts';
import { failGltf } from './errors.ts';
import { isNodeRuntime, nodeModule } from '../platform.ts';
import { checkImageHeader } from '../image-headers.ts';
import { defaultResourcePolicy, type ResolvedResourcePolicy } from '../resource-policy.ts';

export type ImageFormat = 'png' | 'jpeg' | 'webp' | 'ktx2' | 'avif' | 'unknown';

export function sniffImageFormat(bytes: Uint8Array): ImageFormat {
  const b = bytes;
  const ascii = (start: number, text: string): boolean => [...text].every((ch, i) => b[start + i] === ch.charCodeAt(0));
  if (b.length >= 8 && b[0] === 0x89 && ascii(1, 'PNG')) return 'png';
  if (b.length >= 3 && b[0] === 0xff && b[1] === 0xd8 && b[2] === 0xff) return 'jpeg';
  if (b.length >= 12 && ascii(0, 'RIFF') && ascii(8, 'WEBP')) return 'webp';
  if (b.length >= 12 && b[0] === 0xab && ascii(1, 'KTX 20') && b[7] === 0xbb) return 'ktx2';
  if (b.length >= 12 && ascii(4, 'ftyp') && (ascii(8, 'avif') || ascii(8, 'avis'))) return 'avif';
  return 'unknown';
}

export interface DecodedImage {
  image: WavefrontImageInput;
  /** Notes for the loader's warnings (e.g. 16-bit reduced to 8). */
  notes: string[];
}

/**
 * Decodes `bytes`; `field` names the glTF image for errors. The header's size is checked against
 * `policy` before a decoder allocates anything.
 */
export async function decodeImage(bytes: Uint8Array, field: string, policy: ResolvedResourcePolicy = defaultResourcePolicy): Promise<DecodedImage> {
  checkImageHeader(bytes, { code: 'INVALID_GLTF', field }, policy);
  const format = sniffImageFormat(bytes);
  if (format === 'unknown') failGltf(field, 'the image is not PNG, JPEG, WebP, AVIF or KTX2 data');
  try {
    if (format === 'ktx2') return { image: await (await import('./codecs/ktx2.ts')).decodeKtx2(bytes), notes: [] };
    if (!isNodeRuntime() && typeof createImageBitmap === 'function' && typeof OffscreenCanvas === 'function') return { image: await decodeWithBrowser(bytes, format), notes: [] };
    if (format === 'png') return await decodePng(bytes);
    if (format === 'jpeg') return { image: await decodeJpeg(bytes), notes: [] };
    if (format === 'avif') return { image: await (await import('./codecs/avif.ts')).decodeAvif(bytes), notes: [] };
    return { image: await decodeWebp(bytes), notes: [] };
  } catch (error) {
    failGltf(field, `the ${format.toUpperCase()} image does not decode: ${(error as Error).message}`, error);
  }
}

async function decodeWithBrowser(bytes: Uint8Array, format: ImageFormat): Promise<WavefrontImageInput> {
  const blob = new Blob([bytes as Uint8Array<ArrayBuffer>], { type: `image/${format}` });
  const bitmap = await createImageBitmap(blob, { premultiplyAlpha: 'none', colorSpaceConversion: 'none' });
  try {
    const canvas = new OffscreenCanvas(bitmap.width, bitmap.height);
    const context = canvas.getContext('2d');
    if (context === null) throw new Error('no 2D context');
    context.drawImage(bitmap, 0, 0);
    const { data } = context.getImageData(0, 0, bitmap.width, bitmap.height);
    return { width: bitmap.width, height: bitmap.height, data: new Uint8Array(data.buffer, data.byteOffset, data.byteLength) };
  } finally {
    bitmap.close();
  }
}

async function decodePng(bytes: Uint8Array): Promise<DecodedImage> {
  const png = await import('fast-png');
  const decoded = png.decode(bytes);
  const { width, height, channels, depth } = decoded;
  const notes: string[] = [];
  const out = new Uint8Array(width * height * 4);
  if (decoded.palette !== undefined) {
    const rgb = png.convertIndexedToRgb(decoded);
    const size = decoded.palette[0]?.length ?? 3;
    for (let p = 0; p < width * height; p++) {
      for (let k = 0; k < 3; k++) out[p * 4 + k] = rgb[p * size + k];
      out[p * 4 + 3] = size === 4 ? rgb[p * size + 3] : 255;
    }
    return { image: { width, height, data: out }, notes };
  }
  // The common case, 8-bit RGBA, is already the layout the renderer takes (tRNS never applies to it).
  if (channels === 4 && depth === 8) return { image: { width, height, data: new Uint8Array(decoded.data.buffer, decoded.data.byteOffset, width * height * 4) }, notes };
  const samples = unpackSamples(decoded.data, width, height, channels, depth);
  const max = 2 ** depth - 1;
  // 16-bit channels are rounded to 8 bits, the precision of the renderer's textures (as browsers'
  // decoders do too): not worth a warning, a rounding well below what the slots resolve.
  const to8 = (v: number): number => (depth === 8 ? v : Math.round((v * 255) / max));
  const key = decoded.transparency;
  for (let p = 0; p < width * height; p++) {
    const s = p * channels;
    const grey = channels <= 2;
    const r = samples[s];
    const g = grey ? r : samples[s + 1];
    const b = grey ? r : samples[s + 2];
    let a = channels === 2 ? samples[s + 1] : channels === 4 ? samples[s + 3] : max;
    // tRNS colour key (PNG 11.3.2.1): that single grey level or RGB colour is fully transparent.
    if (key !== undefined && key.length > 0 && (channels === 1 || channels === 3)) {
      if (grey ? r === key[0] : r === key[0] && g === key[1] && b === key[2]) a = 0;
    }
    out[p * 4] = to8(r);
    out[p * 4 + 1] = to8(g);
    out[p * 4 + 2] = to8(b);
    out[p * 4 + 3] = to8(a);
  }
  return { image: { width, height, data: out }, notes };
}

/** Samples of 1/2/4-bit images arrive packed, rows padded to whole bytes (PNG 7.2); unpack them. */
function unpackSamples(data: ArrayLike<number>, width: number, height: number, channels: number, depth: number): ArrayLike<number> {
  if (depth >= 8) return data;
  const perRow = width * channels;
  const rowBytes = Math.ceil((perRow * depth) / 8);
  const out = new Uint8Array(perRow * height);
  const mask = (1 << depth) - 1;
  for (let y = 0; y < height; y++) {
    for (let i = 0; i < perRow; i++) {
      const bit = i * depth;
      const byte = data[y * rowBytes + (bit >> 3)];
      out[y * perRow + i] = (byte >> (8 - depth - (bit & 7))) & mask;
    }
  }
  return out;
}

async function decodeJpeg(bytes: Uint8Array): Promise<WavefrontImageInput> {
  const jpeg = (await import('jpeg-js')).default;
  const decoded = jpeg.decode(bytes, { useTArray: true, formatAsRGBA: true, tolerantDecoding: false });
  return { width: decoded.width, height: decoded.height, data: decoded.data };
}

interface WebpWasm {
  decode(buffer: ArrayBuffer): Promise<{ width: number; height: number; data: Uint8ClampedArray } | null>;
}

async function decodeWebp(bytes: Uint8Array): Promise<WavefrontImageInput> {
  // webp-wasm (libwebp built by Squoosh, Node target) finds its .wasm next to itself, which works
  // from both the ES module and the CommonJS builds of this package.
  const webp = (await nodeModule<{ default: WebpWasm }>('webp-wasm')).default;
  const exact = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength) as ArrayBuffer;
  const decoded = await webp.decode(exact);
  if (decoded === null || decoded === undefined || decoded.width <= 0) throw new Error('libwebp rejected the data');
  return { width: decoded.width, height: decoded.height, data: new Uint8Array(decoded.data.buffer, decoded.data.byteOffset, decoded.data.byteLength) };
}
