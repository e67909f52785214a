/**
 * Structural similarity (SSIM), Wang, Bovik, Sheikh and Simoncelli, "Image Quality Assessment:
 * From Error Visibility to Structural Similarity", IEEE TIP 13(4), 2004, as their reference
 * ssim_index.m computes it: an 11x11 circular-symmetric Gaussian window (sigma 1.5, normalised to
 * sum 1), K1 = 0.01, K2 = 0.03, C1 = (K1 L)^2, C2 = (K2 L)^2, local statistics only where the window
 * fits inside the image ("valid" filtering), and the mean of the SSIM map (eq. 13 and 17). No
 * automatic downsampling is applied (the later ssim.m's scale heuristic is not part of the paper).
 */
import { GpuRendererError } from '../../errors/gpu-renderer-error.ts';
import type { Rgba8Image } from '../../io/images/png.ts';

export interface GrayImage {
  width: number;
  height: number;
  data: ArrayLike<number>;
}

export interface SsimOptions {
  /** Dynamic range L of the pixel values; default 255 (8-bit). */
  dynamicRange?: number;
  /** Default 0.01. */
  k1?: number;
  /** Default 0.03. */
  k2?: number;
}

export const ssimWindowSize = 11;
export const ssimWindowSigma = 1.5;

/** The normalised 1D Gaussian whose outer product is the 11x11 window. */
function gaussianTaps(): Float64Array {
  const taps = new Float64Array(ssimWindowSize);
  const r = (ssimWindowSize - 1) / 2;
  let sum = 0;
  for (let i = 0; i < ssimWindowSize; i++) {
    taps[i] = Math.exp(-((i - r) ** 2) / (2 * ssimWindowSigma * ssimWindowSigma));
    sum += taps[i];
  }
  for (let i = 0; i < ssimWindowSize; i++) taps[i] /= sum;
  return taps;
}

/** Separable "valid" filtering of `src` (w x h) with the window: output (w - 10) x (h - 10). */
function filterValid(src: Float64Array, w: number, h: number, taps: Float64Array): Float64Array {
  const ow = w - ssimWindowSize + 1;
  const oh = h - ssimWindowSize + 1;
  const rows = new Float64Array(ow * h);
  for (let y = 0; y < h; y++) {
    for (let x = 0; x < ow; x++) {
      let s = 0;
      for (let k = 0; k < ssimWindowSize; k++) s += taps[k] * src[y * w + x + k];
      rows[y * ow + x] = s;
    }
  }
  const out = new Float64Array(ow * oh);
  for (let y = 0; y < oh; y++) {
    for (let x = 0; x < ow; x++) {
      let s = 0;
      for (let k = 0; k < ssimWindowSize; k++) s += taps[k] * rows[(y + k) * ow + x];
      out[y * ow + x] = s;
    }
  }
  return out;
}

function requireGray(image: GrayImage, field: string): void {
  const { width, height, data } = image ?? ({} as GrayImage);
  if (!Number.isInteger(width) || !Number.isInteger(height) || width < ssimWindowSize || height < ssimWindowSize) {
    throw new GpuRendererError('INVALID_OPTION', `SSIM needs an image of at least ${ssimWindowSize}x${ssimWindowSize}, got ${width}x${height}`, { field });
  }
  if (!data || data.length !== width * height) throw new GpuRendererError('INVALID_OPTION', `expected ${width * height} values`, { field: `${field}.data` });
}

/** The SSIM map (size (w - 10) x (h - 10)) of two single-channel images. */
export function ssimMap(test: GrayImage, reference: GrayImage, options: SsimOptions = {}): { width: number; height: number; data: Float64Array } {
  requireGray(test, 'test');
  requireGray(reference, 'reference');
  if (test.width !== reference.width || test.height !== reference.height) {
    throw new GpuRendererError('INVALID_OPTION', 'expected the size of the reference', { field: 'test' });
  }
  const L = options.dynamicRange ?? 255;
  const k1 = options.k1 ?? 0.01;
  const k2 = options.k2 ?? 0.03;
  for (const [field, v] of [
    ['dynamicRange', L],
    ['k1', k1],
    ['k2', k2],
  ] as const) {
    if (!(typeof v === 'number' && Number.isFinite(v) && v > 0)) throw new GpuRendererError('INVALID_OPTION', `expected a finite number > 0, got ${String(v)}`, { field });
  }
  const c1 = (k1 * L) ** 2;
  const c2 = (k2 * L) ** 2;
  const { width: w, height: h } = reference;
  const n = w * h;
  const x = Float64Array.from(test.data);
  const y = Float64Array.from(reference.data);
  const xx = new Float64Array(n);
  const yy = new Float64Array(n);
  const xy = new Float64Array(n);
  for (let i = 0; i < n; i++) {
    xx[i] = x[i] * x[i];
    yy[i] = y[i] * y[i];
    xy[i] = x[i] * y[i];
  }
  const taps = gaussianTaps();
  const [mx, my, sxx, syy, sxy] = [x, y, xx, yy, xy].map((img) => filterValid(img, w, h, taps));
  const out = new Float64Array(mx.length);
  for (let i = 0; i < out.length; i++) {
    const mux = mx[i];
    const muy = my[i];
    const varX = sxx[i] - mux * mux;
    const varY = syy[i] - muy * muy;
    const cov = sxy[i] - mux * muy;
    out[i] = ((2 * mux * muy + c1) * (2 * cov + c2)) / ((mux * mux + muy * muy + c1) * (varX + varY + c2));
  }
  return { width: w - ssimWindowSize + 1, height: h - ssimWindowSize + 1, data: out };
}

/** Mean SSIM (MSSIM, eq. 17 of the paper) of two single-channel images; 1 for identical images. */
export function structuralSimilarity(test: GrayImage, reference: GrayImage, options: SsimOptions = {}): number {
  const map = ssimMap(test, reference, options).data;
  let sum = 0;
  for (let i = 0; i < map.length; i++) sum += map[i];
  return sum / map.length;
}

/**
 * Luma of 8-bit RGBA as MATLAB's rgb2gray (Rec. 601: 0.298936 R + 0.587043 G + 0.114021 B), the
 * grey image Wang et al.'s reference code is run on for colour inputs.
 */
export function rgba8Luma(image: Rgba8Image): Float64Array {
  const out = new Float64Array(image.width * image.height);
  for (let p = 0; p < out.length; p++) {
    out[p] = 0.298936021293775 * image.data[4 * p] + 0.587043074451121 * image.data[4 * p + 1] + 0.114020904255103 * image.data[4 * p + 2];
  }
  return out;
}

/** Mean SSIM of two 8-bit RGBA images on their luma (L = 255). */
export function ssimRgba8(test: Rgba8Image, reference: Rgba8Image): number {
  for (const [field, image] of [
    ['test', test],
    ['reference', reference],
  ] as const) {
    if (!image || image.data.length !== image.width * image.height * 4) throw new GpuRendererError('INVALID_OPTION', 'expected RGBA8 data', { field: `${field}.data` });
  }
  const { width, height } = reference;
  return structuralSimilarity({ width: test.width, height: test.height, data: rgba8Luma(test) }, { width, height, data: rgba8Luma(reference) });
}
