/**
 * CPU reference of Cycles' adaptive sampling stop test (intern/cycles/kernel/film/
 * adaptive_sampling.h: film_adaptive_sampling_convergence_check and _filter_x / _filter_y), for the
 * GPU port to match. Per pixel it compares the estimate from all samples (I) with the estimate from
 * half of them (A, Cycles' auxiliary buffer: every other sample, weighted 2), the per-pixel error of
 * Dammertz, Hanika, Keller and Lensch, "A Hierarchical Automatic Stopping Condition for Monte Carlo
 * Global Illumination" (WSCG 2010, section 2.1):
 *
 *   error = (|I.r - A.r| + |I.g - A.g| + |I.b - A.b|) / (1e-4 + n(I.r + I.g + I.b)),
 *   n(s) = sqrt(s) for s < 1, else s,
 *
 * a pixel converges when error < threshold, and any unconverged pixel keeps its 3x3 neighbourhood
 * sampling (a box dilation in x, then in y). Pixels with fewer than the minimum samples are never
 * converged. Stopping only decides how many samples a pixel gets; each pixel's estimate stays the
 * plain mean of the samples it received (no reweighting).
 */
import { GpuRendererError } from '../../errors/gpu-renderer-error.ts';
import { requireLinearRgbaImage, type LinearRgbaImage } from '../../io/images/linear-image.ts';

export interface AdaptiveConvergenceOptions {
  /** Noise threshold (Cycles' "Noise Threshold"), > 0. */
  threshold: number;
  /** Pixels with fewer samples keep sampling regardless of their error; default 0. */
  minimumSamplesPerPixel?: number;
  /** Film exposure multiplying both estimates before the test (Cycles' film exposure); default 1. */
  exposure?: number;
}

export interface AdaptiveConvergenceResult {
  /** 1 where the pixel stops sampling, 0 where it continues (after the 3x3 dilation). */
  converged: Uint8Array;
  /** The per-pixel error before dilation (Infinity below the minimum sample count). */
  error: Float32Array;
  /** Pixels that keep sampling. */
  activePixels: number;
}

/** Cycles' error normalisation: sqrt(intensity) below 1, intensity itself above (fewer samples for highlights). */
export function adaptiveSamplingError(ir: number, ig: number, ib: number, ar: number, ag: number, ab: number): number {
  const difference = Math.abs(ir - ar) + Math.abs(ig - ag) + Math.abs(ib - ab);
  const intensity = ir + ig + ib;
  const normalize = intensity < 1 ? Math.sqrt(intensity) : intensity;
  return difference / (0.0001 + normalize);
}

/**
 * Which pixels have converged. `full` holds each pixel's mean over all its samples, `half` the mean
 * over its even-indexed samples (Cycles' aux buffer divided by the sample count); `samples` is the
 * per-pixel sample count (or one count for all pixels).
 */
export function adaptiveConvergedMask(
  full: LinearRgbaImage,
  half: LinearRgbaImage,
  samples: number | Uint32Array,
  options: AdaptiveConvergenceOptions,
): AdaptiveConvergenceResult {
  const pixels = requireLinearRgbaImage(full, 'full');
  requireLinearRgbaImage(half, 'half');
  const { width, height } = full;
  if (half.width !== width || half.height !== height) throw new GpuRendererError('INVALID_OPTION', `expected ${width}x${height} like full`, { field: 'half' });
  if (typeof samples === 'number') {
    if (!Number.isInteger(samples) || samples < 0) throw new GpuRendererError('INVALID_OPTION', `expected an integer >= 0, got ${samples}`, { field: 'samples' });
  } else if (!(samples instanceof Uint32Array) || samples.length !== pixels) {
    throw new GpuRendererError('INVALID_OPTION', `expected a number or a Uint32Array of ${pixels} counts`, { field: 'samples' });
  }
  const threshold = options?.threshold;
  if (typeof threshold !== 'number' || !Number.isFinite(threshold) || threshold <= 0) {
    throw new GpuRendererError('INVALID_OPTION', `expected a finite number > 0, got ${String(threshold)}`, { field: 'threshold' });
  }
  const minimum = options.minimumSamplesPerPixel ?? 0;
  if (!Number.isInteger(minimum) || minimum < 0) throw new GpuRendererError('INVALID_OPTION', `expected an integer >= 0, got ${minimum}`, { field: 'minimumSamplesPerPixel' });
  const exposure = options.exposure ?? 1;
  if (typeof exposure !== 'number' || !Number.isFinite(exposure) || exposure <= 0) {
    throw new GpuRendererError('INVALID_OPTION', `expected a finite number > 0, got ${String(exposure)}`, { field: 'exposure' });
  }

  const error = new Float32Array(pixels);
  const own = new Uint8Array(pixels);
  for (let p = 0; p < pixels; p++) {
    const n = typeof samples === 'number' ? samples : samples[p];
    if (n < minimum || n === 0) {
      error[p] = Infinity;
      continue;
    }
    const i = 4 * p;
    const e = adaptiveSamplingError(
      full.data[i] * exposure,
      full.data[i + 1] * exposure,
      full.data[i + 2] * exposure,
      half.data[i] * exposure,
      half.data[i + 1] * exposure,
      half.data[i + 2] * exposure,
    );
    error[p] = e;
    // NaN errors (invalid estimates) never converge.
    own[p] = e < threshold ? 1 : 0;
  }
  // Dilate "keeps sampling" by one pixel along x, then along y: a 3x3 box (filter_x, filter_y).
  const rows = new Uint8Array(own);
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const p = y * width + x;
      if ((x > 0 && own[p - 1] === 0) || (x + 1 < width && own[p + 1] === 0)) rows[p] = 0;
    }
  }
  const converged = new Uint8Array(rows);
  let activePixels = 0;
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const p = y * width + x;
      if ((y > 0 && rows[p - width] === 0) || (y + 1 < height && rows[p + width] === 0)) converged[p] = 0;
      if (converged[p] === 0) activePixels++;
    }
  }
  return { converged, error, activePixels };
}

/**
 * Cycles' automatic settings for a sample budget (Integrator::get_adaptive_sampling): threshold
 * max(0.001, 1 / maxSamples) and minimum samples max(4, ceil(16 / threshold^0.3)), e.g. 0.1 -> 32,
 * 0.01 -> 64, 0.001 -> 128.
 */
export function defaultAdaptiveSamplingParameters(maxSamplesPerPixel: number, threshold?: number): { threshold: number; minimumSamplesPerPixel: number } {
  if (!Number.isInteger(maxSamplesPerPixel) || maxSamplesPerPixel < 1) {
    throw new GpuRendererError('INVALID_OPTION', `expected an integer >= 1, got ${maxSamplesPerPixel}`, { field: 'maxSamplesPerPixel' });
  }
  const t = threshold ?? Math.max(0.001, 1 / maxSamplesPerPixel);
  if (!Number.isFinite(t) || t <= 0) throw new GpuRendererError('INVALID_OPTION', `expected a finite number > 0, got ${t}`, { field: 'threshold' });
  return { threshold: t, minimumSamplesPerPixel: Math.max(4, Math.ceil(16 / Math.pow(t, 0.3))) };
}
