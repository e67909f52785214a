/**
 * Radiance RGBE (.hdr) reader for `-Y H +X W` images: flat, old-style (repeat-pixel) and new-style
 * (per-component) run-length encoded scanlines; `EXPOSURE=` header lines are divided out so the
 * result is the radiance that was written.
 */
import { GpuRendererError } from '../../errors/gpu-renderer-error.ts';
import { defaultResourcePolicy } from '../../io/resource-policy.ts';
import type { LinearRgbaImage } from './linear-image.ts';

function invalid(message: string): never {
  throw new GpuRendererError('INVALID_OPTION', `not a readable Radiance .hdr file: ${message}`, { field: 'bytes' });
}

/** Radiance's colr_color (color.c): byte b with exponent byte e decodes to (b + 0.5) * 2^(e - 136). */
function rgbeToLinear(scanline: Uint8Array, width: number, exposure: number, out: Float32Array, rowOffset: number): void {
  for (let x = 0; x < width; x++) {
    const e = scanline[4 * x + 3];
    const o = rowOffset + 4 * x;
    if (e === 0) {
      out[o] = out[o + 1] = out[o + 2] = 0;
    } else {
      const f = 2 ** (e - 136) / exposure;
      out[o] = (scanline[4 * x] + 0.5) * f;
      out[o + 1] = (scanline[4 * x + 1] + 0.5) * f;
      out[o + 2] = (scanline[4 * x + 2] + 0.5) * f;
    }
    out[o + 3] = 1;
  }
}

/**
 * Decodes a Radiance .hdr file into linear RGBA float32, top row first (alpha 1). A resolution
 * over `limits.maxImageDimension` (default 16384) per side or `limits.maxDecodedBytes` (default
 * 2 GiB) of texels is refused before anything is allocated.
 */
export function decodeHdr(bytes: Uint8Array, limits: { maxImageDimension?: number; maxDecodedBytes?: number } = {}): LinearRgbaImage {
  if (!(bytes instanceof Uint8Array)) throw new GpuRendererError('INVALID_OPTION', 'expected a Uint8Array', { field: 'bytes' });
  let pos = 0;
  const readLine = (): string => {
    const start = pos;
    while (pos < bytes.length && bytes[pos] !== 0x0a) pos++;
    if (pos >= bytes.length) invalid('header ends early');
    // latin1, not String.fromCharCode(...bytes): a long line would overflow the argument list.
    return new TextDecoder('latin1').decode(bytes.subarray(start, pos++));
  };
  const first = readLine();
  if (!first.startsWith('#?')) invalid('missing the #? signature');
  let exposure = 1;
  for (let line = readLine(); line !== ''; line = readLine()) {
    if (line.startsWith('FORMAT=') && line.trim() !== 'FORMAT=32-bit_rle_rgbe') invalid(`unsupported ${line.trim()}`);
    if (line.startsWith('EXPOSURE=')) exposure *= Number(line.slice(9));
  }
  if (!(exposure > 0) || !Number.isFinite(exposure)) invalid('bad EXPOSURE');
  const resolution = /^-Y (\d+) \+X (\d+)$/.exec(readLine().trim());
  if (!resolution) invalid('only -Y H +X W orientation is supported');
  const height = Number(resolution[1]);
  const width = Number(resolution[2]);
  if (width < 1 || height < 1) invalid('empty image');
  const maxSide = limits.maxImageDimension ?? defaultResourcePolicy.maxImageDimension;
  if (width > maxSide || height > maxSide) invalid(`${width} x ${height} texels exceed the largest side of ${maxSide}`);
  if (width * height * 16 > (limits.maxDecodedBytes ?? defaultResourcePolicy.maxDecodedBytes)) invalid(`${width} x ${height} float texels exceed the decoded-bytes limit`);
  if (bytes.length - pos < 4 * height) invalid(`pixel data ends early: ${height} scanlines need at least ${4 * height} bytes`);
  const data = new Float32Array(width * height * 4);
  const scanline = new Uint8Array(width * 4);
  const need = (n: number): void => {
    if (pos + n > bytes.length) invalid('pixel data ends early');
  };
  for (let y = 0; y < height; y++) {
    need(4);
    const newRle = width >= 8 && width <= 0x7fff && bytes[pos] === 2 && bytes[pos + 1] === 2 && (bytes[pos + 2] & 0x80) === 0;
    if (newRle) {
      if (((bytes[pos + 2] << 8) | bytes[pos + 3]) !== width) invalid(`scanline ${y} has the wrong width`);
      pos += 4;
      for (let c = 0; c < 4; c++) {
        for (let x = 0; x < width; ) {
          need(1);
          const count = bytes[pos++];
          if (count > 128) {
            const run = count - 128;
            if (x + run > width) invalid(`run overflows scanline ${y}`);
            need(1);
            const value = bytes[pos++];
            for (let k = 0; k < run; k++) scanline[4 * x++ + c] = value;
          } else {
            if (count === 0 || x + count > width) invalid(`bad literal count in scanline ${y}`);
            need(count);
            for (let k = 0; k < count; k++) scanline[4 * x++ + c] = bytes[pos++];
          }
        }
      }
    } else {
      // Flat pixels, where (1, 1, 1, n) repeats the previous pixel n << shift times (old-style RLE).
      let shift = 0;
      for (let x = 0; x < width; ) {
        need(4);
        if (bytes[pos] === 1 && bytes[pos + 1] === 1 && bytes[pos + 2] === 1) {
          if (x === 0) invalid(`repeat with no previous pixel in scanline ${y}`);
          const repeat = bytes[pos + 3] << shift;
          if (x + repeat > width) invalid(`repeat overflows scanline ${y}`);
          for (let k = 0; k < repeat; k++, x++) scanline.copyWithin(4 * x, 4 * (x - 1), 4 * x);
          shift += 8;
        } else {
          scanline.set(bytes.subarray(pos, pos + 4), 4 * x++);
          shift = 0;
        }
        pos += 4;
      }
    }
    rgbeToLinear(scanline, width, exposure, data, 4 * y * width);
  }
  return { width, height, data };
}
