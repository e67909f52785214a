import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import type { DecodeBudget } from '../io/resource-policy.ts';
import { MAX_ENVIRONMENT_MAP_DIMENSION } from './environment-map.ts';

/** A decoded HDR image: RGBA float32 (alpha 1), row-major, top row first. */
export interface DecodedHdrImage {
  width: number;
  height: number;
  data: Float32Array;
}

const MIN_RLE_WIDTH = 8;
const MAX_RLE_WIDTH = 0x7fff;

function invalid(field: string, message: string): never {
  throw new GpuRendererError('INVALID_ENVIRONMENT', `Radiance HDR: ${message}`, { field });
}

/** True when `bytes` start with a Radiance header signature ("#?"). */
export function isRadianceHdr(bytes: Uint8Array): boolean {
  return bytes.length >= 2 && bytes[0] === 0x23 && bytes[1] === 0x3f;
}

/**
 * Decodes a Radiance RGBE picture (Greg Ward's .hdr / .pic, "Real Pixels", Graphics Gems II, 1991;
 * the format as Radiance's color.c reads it): header lines up to a blank line, a resolution string,
 * then scanlines that are flat RGBE, old-style run-length (1, 1, 1, n repeats) or new-style RLE
 * (2, 2, width, then each channel run-length coded separately).
 *
 * Supports `FORMAT=32-bit_rle_rgbe`, cumulative `EXPOSURE=` (divided out, so texels are the
 * original radiance), and the four row-major orientations `[+-]Y H [+-]X W` (the common one is
 * `-Y H +X W`, top row first). A texel is (mantissa + 0.5) * 2^(exponent - 136), Radiance's
 * colr_color. Errors: `INVALID_ENVIRONMENT` naming `field`. The resolution is checked against the
 * largest map side, and the texels charged to `budget` (a load's resource budget), before any
 * allocation; each scanline needs at least 4 bytes, so a short file is refused before decoding.
 */
export function decodeRadianceHdr(bytes: Uint8Array, field = 'source', budget?: DecodeBudget): DecodedHdrImage {
  if (!isRadianceHdr(bytes)) invalid(field, 'missing the "#?" signature');
  let pos = 0;
  const readLine = (): string => {
    const start = pos;
    while (pos < bytes.length && bytes[pos] !== 0x0a) pos++;
    if (pos >= bytes.length) invalid(field, 'truncated header');
    const line = new TextDecoder('latin1').decode(bytes.subarray(start, pos));
    pos++;
    return line.replace(/\r$/, '');
  };
  readLine(); // signature
  let exposure = 1;
  let format = '';
  for (;;) {
    const line = readLine();
    if (line === '') break;
    if (line.startsWith('FORMAT=')) format = line.slice(7).trim();
    else if (line.startsWith('EXPOSURE=')) {
      const e = Number(line.slice(9));
      if (!(e > 0) || !Number.isFinite(e)) invalid(field, `bad EXPOSURE "${line}"`);
      exposure *= e;
    }
  }
  if (format !== '' && format !== '32-bit_rle_rgbe') invalid(field, `unsupported FORMAT "${format}" (only 32-bit_rle_rgbe)`);
  const resolution = readLine().trim();
  const m = /^([+-])Y\s+(\d+)\s+([+-])X\s+(\d+)$/.exec(resolution);
  if (!m) {
    if (/^[+-]X\s+\d+\s+[+-]Y\s+\d+$/.test(resolution)) invalid(field, `column-major orientation "${resolution}" is not supported`);
    invalid(field, `bad resolution string "${resolution}"`);
  }
  const height = Number(m[2]);
  const width = Number(m[4]);
  if (!(width > 0 && height > 0)) invalid(field, `empty image "${resolution}"`);
  if (width > MAX_ENVIRONMENT_MAP_DIMENSION || height > MAX_ENVIRONMENT_MAP_DIMENSION) {
    invalid(field, `${width} x ${height} texels exceed the largest map side of ${MAX_ENVIRONMENT_MAP_DIMENSION} ("${resolution.slice(0, 60)}")`);
  }
  if (bytes.length - pos < 4 * height) invalid(field, `truncated pixel data: ${height} scanlines need at least ${4 * height} bytes, ${bytes.length - pos} follow the header`);
  // RGBE bytes, the float texels and the validated map's copy.
  budget?.charge(width * height * 36, { code: 'INVALID_ENVIRONMENT', field }, `the ${width} x ${height} Radiance HDR texels`);
  const topDown = m[1] === '-';
  const leftRight = m[3] === '+';
  const rgbe = new Uint8Array(width * height * 4);
  const need = (n: number): void => {
    if (pos + n > bytes.length) invalid(field, `truncated pixel data (scanline data ends at byte ${bytes.length})`);
  };
  for (let y = 0; y < height; y++) {
    const row = y * width * 4;
    const newRle =
      width >= MIN_RLE_WIDTH && width <= MAX_RLE_WIDTH && pos + 4 <= bytes.length && bytes[pos] === 2 && bytes[pos + 1] === 2 && (bytes[pos + 2]! & 0x80) === 0;
    if (newRle) {
      const w = (bytes[pos + 2]! << 8) | bytes[pos + 3]!;
      if (w !== width) invalid(field, `scanline ${y} has width ${w}, expected ${width}`);
      pos += 4;
      for (let c = 0; c < 4; c++) {
        let x = 0;
        while (x < width) {
          need(1);
          let count = bytes[pos++]!;
          if (count > 128) {
            count -= 128;
            if (x + count > width) invalid(field, `run overflows scanline ${y}`);
            need(1);
            const value = bytes[pos++]!;
            for (let k = 0; k < count; k++) rgbe[row + 4 * x++ + c] = value;
          } else {
            if (count === 0 || x + count > width) invalid(field, `bad literal run in scanline ${y}`);
            need(count);
            for (let k = 0; k < count; k++) rgbe[row + 4 * x++ + c] = bytes[pos++]!;
          }
        }
      }
    } else {
      // Flat RGBE, where (1, 1, 1, n) repeats the previous pixel n << shift times (Radiance's
      // oldreadcolrs; consecutive repeat pixels extend the count by 8 bits each).
      let x = 0;
      let shift = 0;
      while (x < width) {
        need(4);
        if (bytes[pos] === 1 && bytes[pos + 1] === 1 && bytes[pos + 2] === 1) {
          if (x === 0) invalid(field, `repeat marker with no previous pixel in scanline ${y}`);
          const count = bytes[pos + 3]! << shift;
          if (x + count > width) invalid(field, `repeat overflows scanline ${y}`);
          for (let k = 0; k < count; k++, x++) rgbe.copyWithin(row + 4 * x, row + 4 * (x - 1), row + 4 * x);
          shift += 8;
        } else {
          rgbe.set(bytes.subarray(pos, pos + 4), row + 4 * x);
          x++;
          shift = 0;
        }
        pos += 4;
      }
    }
  }
  const data = new Float32Array(width * height * 4);
  for (let y = 0; y < height; y++) {
    const outY = topDown ? y : height - 1 - y;
    for (let x = 0; x < width; x++) {
      const outX = leftRight ? x : width - 1 - x;
      const s = 4 * (y * width + x);
      const d = 4 * (outY * width + outX);
      const e = rgbe[s + 3]!;
      if (e !== 0) {
        const f = 2 ** (e - 136) / exposure;
        data[d] = (rgbe[s]! + 0.5) * f;
        data[d + 1] = (rgbe[s + 1]! + 0.5) * f;
        data[d + 2] = (rgbe[s + 2]! + 0.5) * f;
      }
      data[d + 3] = 1;
    }
  }
  return { width, height, data };
}
