/**
 * Mip levels and downscaled copies of RGBA8 images by area-weighted box filtering: every output
 * texel is the exact mean of the source over its footprint (the output texel's rectangle mapped
 * onto the source, partial texels weighted by the covered fraction), so odd sizes and WebGPU's
 * floor convention for level sizes stay correct. Every level is filtered from level 0 itself, not
 * from the level above, because chaining 2x2 averages is not the footprint mean once a size is odd.
 *
 * Colour data (sRGB-encoded) is averaged in linear light: decoded with the exact sRGB curve
 * (IEC 61966-2-1:1999), averaged, re-encoded and rounded; linear data and alpha are averaged as
 * stored (glTF 2.0 section 3.9: alpha is linear in every texture).
 */
import { srgbToLinear } from '../../color/srgb.ts';
import { fullMipCount, mipLevelSize } from './atlas-layout.ts';

/** How the RGB channels of an image are encoded (alpha is always linear). */
export type TexelEncoding = 'srgb' | 'linear';

export interface Rgba8Image {
  readonly width: number;
  readonly height: number;
  /** RGBA8, row-major, top row first. */
  readonly data: Uint8Array;
  /** Levels 1, 2, ... the image's file stores (validated sizes); see WavefrontImageInput.mipLevels. */
  readonly mipLevels?: readonly Rgba8Image[];
}

const byteToUnit = Float64Array.from({ length: 256 }, (_, i) => i / 255);
const byteToLinear = Float64Array.from({ length: 256 }, (_, i) => srgbToLinear(i / 255));

/** One output size: where each output column starts in the source, and the rows being summed. */
interface ResamplePlan {
  readonly width: number;
  readonly height: number;
  /** Output column x covers source [x * w / width, (x + 1) * w / width): integer and fractional starts. */
  readonly columnStart: Int32Array;
  readonly columnFraction: Float64Array;
  readonly row: Float64Array;
  /** Output rows in progress (at most two overlap one source row when shrinking): row yo uses yo & 1. */
  readonly sums: [Float64Array, Float64Array];
  readonly out: Uint8Array;
}

function plan(sourceWidth: number, sourceHeight: number, width: number, height: number): ResamplePlan {
  if (!(Number.isInteger(width) && Number.isInteger(height) && width >= 1 && height >= 1 && width <= sourceWidth && height <= sourceHeight)) {
    throw new RangeError(`area resampling shrinks only: ${sourceWidth}x${sourceHeight} -> ${width}x${height}`);
  }
  const columnStart = new Int32Array(width + 1);
  const columnFraction = new Float64Array(width + 1);
  for (let x = 0; x <= width; x++) {
    const scaled = x * sourceWidth; // boundary x * w / width, in units of 1 / width
    const whole = Math.floor(scaled / width);
    columnStart[x] = whole;
    columnFraction[x] = (scaled - whole * width) / width;
  }
  return {
    width,
    height,
    columnStart,
    columnFraction,
    row: new Float64Array(width * 4),
    sums: [new Float64Array(width * 4), new Float64Array(width * 4)],
    out: new Uint8Array(width * height * 4),
  };
}

/**
 * linearBounds[k] = the linear value whose sRGB encoding is (k + 0.5) / 255: round(255 srgb(x)) is
 * the number of bounds <= x (the curve is increasing), found by binary search instead of a pow.
 */
const linearBounds = Float64Array.from({ length: 255 }, (_, k) => srgbToLinear((k + 0.5) / 255));

function encodeByte(value: number, srgb: boolean): number {
  if (!srgb) return Math.min(255, Math.max(0, Math.round(value * 255)));
  let lo = 0;
  let hi = 255;
  while (lo < hi) {
    const mid = (lo + hi) >> 1;
    if (linearBounds[mid]! <= value) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}

/**
 * Shrinks `image` to every size in `sizes` (each at most the source size) by area-weighted box
 * filtering, streaming the source once: per source row, prefix sums give every output column's
 * footprint integral, and each row is added to the (at most two) output rows it overlaps.
 */
export function areaResample(image: Rgba8Image, sizes: readonly (readonly [number, number])[], encoding: TexelEncoding): Uint8Array[] {
  const { width: w, height: h, data } = image;
  const srgb = encoding === 'srgb';
  const rgbTable = srgb ? byteToLinear : byteToUnit;
  const plans = sizes.map(([dw, dh]) => plan(w, h, dw, dh));
  // prefix[i * 4 + c] = sum of channel c over source texels 0..i-1 of the current row.
  const prefix = new Float64Array((w + 1) * 4);
  for (let y = 0; y < h; y++) {
    const rowStart = y * w * 4;
    for (let i = 0; i < w; i++) {
      const s = rowStart + i * 4;
      const p = i * 4;
      prefix[p + 4] = prefix[p]! + rgbTable[data[s]!]!;
      prefix[p + 5] = prefix[p + 1]! + rgbTable[data[s + 1]!]!;
      prefix[p + 6] = prefix[p + 2]! + rgbTable[data[s + 2]!]!;
      prefix[p + 7] = prefix[p + 3]! + byteToUnit[data[s + 3]!]!;
    }
    for (const p of plans) {
      resampleRow(p, prefix, w);
      accumulateRow(p, y, h, srgb);
    }
  }
  return plans.map((p) => p.out);
}

/** Horizontal pass: the footprint mean of every output column of the current source row. */
function resampleRow(p: ResamplePlan, prefix: Float64Array, sourceWidth: number): void {
  const scale = p.width / sourceWidth;
  for (let c = 0; c < 4; c++) {
    let previous = integral(prefix, p.columnStart[0]!, p.columnFraction[0]!, c);
    for (let x = 0; x < p.width; x++) {
      const next = integral(prefix, p.columnStart[x + 1]!, p.columnFraction[x + 1]!, c);
      p.row[x * 4 + c] = (next - previous) * scale;
      previous = next;
    }
  }
}

/** Integral of channel c of the row from 0 to i + f (the row is constant over each texel). */
function integral(prefix: Float64Array, i: number, f: number, c: number): number {
  const below = prefix[i * 4 + c]!;
  return f === 0 ? below : below + f * (prefix[(i + 1) * 4 + c]! - below);
}

/** Vertical pass: adds source row y to the output rows it overlaps and emits the finished ones. */
function accumulateRow(p: ResamplePlan, y: number, sourceHeight: number, srgb: boolean): void {
  const dh = p.height;
  // Output row yo covers source [yo * h / dh, (yo + 1) * h / dh); in units of 1 / dh everything is integral.
  const top = y * dh;
  const bottom = (y + 1) * dh;
  const first = Math.floor(top / sourceHeight);
  const last = Math.ceil(bottom / sourceHeight) - 1;
  for (let yo = first; yo <= last; yo++) {
    const overlap = Math.min(bottom, (yo + 1) * sourceHeight) - Math.max(top, yo * sourceHeight);
    const weight = overlap / sourceHeight;
    const sum = p.sums[yo & 1];
    for (let k = 0; k < sum.length; k++) sum[k]! += weight * p.row[k]!;
    if (bottom >= (yo + 1) * sourceHeight) {
      const base = yo * p.width * 4;
      for (let k = 0; k < sum.length; k++) {
        p.out[base + k] = encodeByte(sum[k]!, srgb && (k & 3) !== 3);
        sum[k] = 0;
      }
    }
  }
}

/**
 * The mip chain of `image`: level 0 is the image's own data, level k (WebGPU size
 * max(1, size >> k)) the footprint mean of level 0.
 */
export function generateMipChain(image: Rgba8Image, encoding: TexelEncoding, levels: number = fullMipCount(image.width, image.height)): Uint8Array[] {
  const sizes: [number, number][] = [];
  for (let k = 1; k < levels; k++) sizes.push(mipLevelSize(image.width, image.height, k));
  return [image.data, ...areaResample(image, sizes, encoding)];
}

/**
 * The mip chain of `image`: the levels its file stores (`mipLevels`), as the file's author filtered
 * them, then levels filtered from level 0 for the rest of the `levels` asked for.
 */
export function imageMipChain(image: Rgba8Image, encoding: TexelEncoding, levels: number): Uint8Array[] {
  const stored = (image.mipLevels ?? []).slice(0, levels - 1).map((level) => level.data);
  const sizes: [number, number][] = [];
  for (let k = 1 + stored.length; k < levels; k++) sizes.push(mipLevelSize(image.width, image.height, k));
  return [image.data, ...stored, ...areaResample(image, sizes, encoding)];
}

/** `image` shrunk to `width` x `height` by the same footprint mean. */
export function downscaleImage(image: Rgba8Image, width: number, height: number, encoding: TexelEncoding): Rgba8Image {
  const [data] = areaResample(image, [[width, height]], encoding);
  return { width, height, data: data! };
}
