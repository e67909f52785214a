/**
 * Radiance RGBE (.hdr) writer, after Greg Ward's format description ("Real Pixels", Graphics Gems
 * II, 1991) and the Radiance file format notes: a text header, then `-Y H +X W` scanlines (top row
 * first, left to right) of 4-byte RGBE pixels, each scanline run-length encoded per component
 * ("new-style" RLE) when its width is 8..32767, else stored flat as the format requires.
 */
import { GpuRendererError } from '../../errors/gpu-renderer-error.ts';
import { ByteWriter } from './byte-writer.ts';
import { requireLinearRgbaImage, type LinearRgbaImage } from './linear-image.ts';

/** Shortest run worth encoding as a run (Ward's MINRUNLENGTH). */
const minRunLength = 4;

/**
 * One pixel as RGBE: the largest component v = m * 2^e (m in [0.5, 1)) sets the shared exponent
 * byte e + 128, and each component c is stored as floor(c * 256 / 2^e), Ward's float2rgbe.
 * RGBE cannot hold negative or non-finite values: negatives and NaN store as 0, +Infinity and
 * magnitudes of 2^127 and above as the largest RGBE value; values below 2^-128 store as black.
 */
export function encodeRgbe(r: number, g: number, b: number, out: Uint8Array, offset: number): void {
  const rr = r > 0 ? r : 0;
  const gg = g > 0 ? g : 0;
  const bb = b > 0 ? b : 0;
  const v = Math.max(rr, gg, bb);
  if (!(v >= 2 ** -128)) {
    out[offset] = out[offset + 1] = out[offset + 2] = out[offset + 3] = 0;
    return;
  }
  if (v >= 2 ** 127) {
    // Saturate at the largest exponent; scaleInto caps each byte at 255 (Infinity included).
    scaleInto(rr, gg, bb, 127, out, offset);
    out[offset + 3] = 255;
    return;
  }
  // frexp: v = m * 2^e with m in [0.5, 1); log2 can be off by one near powers of two, so fix up.
  let e = Math.floor(Math.log2(v)) + 1;
  if (v / 2 ** e >= 1) e++;
  else if (v / 2 ** e < 0.5) e--;
  scaleInto(rr, gg, bb, e, out, offset);
  out[offset + 3] = e + 128;
}

function scaleInto(r: number, g: number, b: number, e: number, out: Uint8Array, offset: number): void {
  const scale = 2 ** (8 - e);
  out[offset] = Math.min(255, Math.floor(r * scale));
  out[offset + 1] = Math.min(255, Math.floor(g * scale));
  out[offset + 2] = Math.min(255, Math.floor(b * scale));
}

/** Run-length codes one component plane of a scanline: (128 + n, byte) runs, (n, n bytes) literals. */
function writeRlePlane(plane: Uint8Array, out: ByteWriter): void {
  const n = plane.length;
  const runAt = (i: number): number => {
    let r = 1;
    while (i + r < n && r < 127 && plane[i + r] === plane[i]) r++;
    return r;
  };
  let i = 0;
  while (i < n) {
    const run = runAt(i);
    if (run >= minRunLength) {
      out.u8(128 + run);
      out.u8(plane[i]);
      i += run;
      continue;
    }
    let j = i + 1;
    while (j < n && j - i < 128 && runAt(j) < minRunLength) j++;
    out.u8(j - i);
    out.bytes(plane.subarray(i, j));
    i = j;
  }
}

export interface EncodeHdrOptions {
  /** Text for a `#` comment line in the header; default names this package. */
  comment?: string;
}

/**
 * Encodes linear RGB radiance (alpha ignored) as a Radiance .hdr file. The header records the
 * primaries of linear sRGB / Rec. 709 with a D65 white (`PRIMARIES=`), which the data are in.
 */
export function encodeHdr(image: LinearRgbaImage, options: EncodeHdrOptions = {}): Uint8Array {
  requireLinearRgbaImage(image);
  const { width, height, data } = image;
  const comment = options.comment ?? 'written by @plasius/gpu-renderer';
  if (typeof comment !== 'string' || /[\n\r]/.test(comment) || !/^[\x20-\x7e]*$/.test(comment)) {
    throw new GpuRendererError('INVALID_OPTION', 'expected one line of printable ASCII', { field: 'comment' });
  }
  const out = new ByteWriter();
  out.ascii('#?RADIANCE\n');
  out.ascii(`# ${comment}\n`);
  out.ascii('FORMAT=32-bit_rle_rgbe\n');
  out.ascii('PRIMARIES=0.640 0.330 0.300 0.600 0.150 0.060 0.3127 0.3290\n');
  out.ascii('\n');
  out.ascii(`-Y ${height} +X ${width}\n`);
  const scanline = new Uint8Array(width * 4);
  const plane = new Uint8Array(width);
  const rle = width >= 8 && width <= 0x7fff;
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const i = 4 * (y * width + x);
      encodeRgbe(data[i], data[i + 1], data[i + 2], scanline, 4 * x);
    }
    if (!rle) {
      out.bytes(scanline);
      continue;
    }
    out.u8(2);
    out.u8(2);
    out.u8(width >> 8);
    out.u8(width & 0xff);
    for (let c = 0; c < 4; c++) {
      for (let x = 0; x < width; x++) plane[x] = scanline[4 * x + c];
      writeRlePlane(plane, out);
    }
  }
  return out.toBytes();
}
