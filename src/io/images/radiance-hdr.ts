/**
 * Radiance RGBE pictures (.hdr / .pic): the one reader of the package, used for environment maps,
 * scene files and the image-file API alike.
 */
import { GpuRendererError, type GpuRendererErrorCode } from '../../errors/gpu-renderer-error.ts';
import { DecodeBudget, defaultResourcePolicy } from '../resource-policy.ts';
import type { LinearRgbaImage } from './linear-image.ts';

/** A decoded HDR image: RGBA float32 (alpha 1), row-major, top row first. */
export type DecodedHdrImage = LinearRgbaImage;

/** Where a decode reports errors and what it may allocate. */
export interface DecodeRadianceHdrOptions {
  /** The error field, default 'source'. */
  field?: string;
  /** The error code, default 'INVALID_ENVIRONMENT'. */
  code?: GpuRendererErrorCode;
  /** Largest width or height, default the resource policy's `maxImageDimension` (16384). */
  maxImageDimension?: number;
  /** How the side limit is named in the error, default 'side'. */
  limitName?: string;
  /** A load's resource budget, charged with the decode's allocations before they are made. */
  budget?: DecodeBudget;
  /** Without a `budget`: the most bytes the decode may allocate, default the policy's `maxDecodedBytes`. */
  maxDecodedBytes?: number;
}

const MIN_RLE_WIDTH = 8;
const MAX_RLE_WIDTH = 0x7fff;
/** The RGBE scanlines and the float texels. */
const DECODE_BYTES_PER_TEXEL = 4 + 16;

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
 * colr_color. Errors name `options.field` with `options.code`. The resolution is checked against
 * the largest side, and the allocations charged to the budget, before anything is allocated; each
 * scanline needs at least 4 bytes, so a short file is refused before decoding.
 *
 * The second and third parameters may also be the error field and a budget (the original form).
 */
export function decodeRadianceHdr(bytes: Uint8Array, options: DecodeRadianceHdrOptions | string = {}, budget?: DecodeBudget): DecodedHdrImage {
  const o: DecodeRadianceHdrOptions = typeof options === 'string' ? { field: options, budget } : { ...options, budget: options.budget ?? budget };
  const field = o.field ?? 'source';
  const code = o.code ?? 'INVALID_ENVIRONMENT';
  const invalid: (message: string) => never = (message) => {
    throw new GpuRendererError(code, `Radiance HDR: ${message}`, { field });
  };
  if (!(bytes instanceof Uint8Array)) invalid('expected the file as a Uint8Array');
  if (!isRadianceHdr(bytes)) invalid('missing the "#?" signature');
  let pos = 0;
  const readLine = (): string => {
    const start = pos;
    while (pos < bytes.length && bytes[pos] !== 0x0a) pos++;
    if (pos >= bytes.length) invalid('truncated header');
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
      if (!(e > 0) || !Number.isFinite(e)) invalid(`bad EXPOSURE "${line}"`);
      exposure *= e;
    }
  }
  if (format !== '' && format !== '32-bit_rle_rgbe') invalid(`unsupported FORMAT "${format}" (only 32-bit_rle_rgbe)`);
  const resolution = readLine().trim();
  const m = /^([+-])Y\s+(\d+)\s+([+-])X\s+(\d+)$/.exec(resolution);
  if (!m) {
    if (/^[+-]X\s+\d+\s+[+-]Y\s+\d+$/.test(resolution)) invalid(`column-major orientation "${resolution}" is not supported`);
    invalid(`bad resolution string "${resolution}"`);
  }
  const height = Number(m[2]);
  const width = Number(m[4]);
  if (!(width > 0 && height > 0)) invalid(`empty image "${resolution}"`);
  const maxSide = o.maxImageDimension ?? defaultResourcePolicy.maxImageDimension;
  if (width > maxSide || height > maxSide) invalid(`${width} x ${height} texels exceed the largest ${o.limitName ?? 'side'} of ${maxSide} ("${resolution.slice(0, 60)}")`);
  if (bytes.length - pos < 4 * height) invalid(`truncated pixel data: ${height} scanlines need at least ${4 * height} bytes, ${bytes.length - pos} follow the header`);
  const charged = o.budget ?? new DecodeBudget(o.maxDecodedBytes ?? defaultResourcePolicy.maxDecodedBytes);
  charged.charge(width * height * DECODE_BYTES_PER_TEXEL, { code, field }, `the ${width} x ${height} Radiance HDR texels`);
  const topDown = m[1] === '-';
  const leftRight = m[3] === '+';
  const rgbe = new Uint8Array(width * height * 4);
  const need = (n: number): void => {
    if (pos + n > bytes.length) invalid(`truncated pixel data (scanline data ends at byte ${bytes.length})`);
  };
  for (let y = 0; y < height; y++) {
    const row = y * width * 4;
    const newRle =
      width >= MIN_RLE_WIDTH && width <= MAX_RLE_WIDTH && pos + 4 <= bytes.length && bytes[pos] === 2 && bytes[pos + 1] === 2 && (bytes[pos + 2]! & 0x80) === 0;
    if (newRle) {
      const w = (bytes[pos + 2]! << 8) | bytes[pos + 3]!;
      if (w !== width) invalid(`scanline ${y} has width ${w}, expected ${width}`);
      pos += 4;
      for (let c = 0; c < 4; c++) {
        let x = 0;
        while (x < width) {
          need(1);
          let count = bytes[pos++]!;
          if (count > 128) {
            count -= 128;
            if (x + count > width) invalid(`run overflows scanline ${y}`);
            need(1);
            const value = bytes[pos++]!;
            for (let k = 0; k < count; k++) rgbe[row + 4 * x++ + c] = value;
          } else {
            if (count === 0 || x + count > width) invalid(`bad literal run in scanline ${y}`);
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
          if (x === 0) invalid(`repeat marker with no previous pixel in scanline ${y}`);
          const count = bytes[pos + 3]! << shift;
          if (x + count > width) invalid(`repeat overflows scanline ${y}`);
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

/**
 * Decodes a Radiance .hdr file into linear RGBA float32, top row first (alpha 1), as the
 * image-file API reads it back: errors are `INVALID_OPTION` naming `bytes`. A resolution over
 * `limits.maxImageDimension` (default 16384) per side or `limits.maxDecodedBytes` (default 2 GiB)
 * of allocations is refused before anything is allocated.
 */
export function decodeHdr(bytes: Uint8Array, limits: { maxImageDimension?: number; maxDecodedBytes?: number } = {}): LinearRgbaImage {
  return decodeRadianceHdr(bytes, { field: 'bytes', code: 'INVALID_OPTION', maxImageDimension: limits.maxImageDimension, maxDecodedBytes: limits.maxDecodedBytes });
}
