/**
 * Per-pixel error metrics between a test image and a reference, over the R, G and B channels of
 * linear RGBA float images (alpha ignored). All are means over pixels and the three channels.
 */
import { GpuRendererError } from '../../errors/gpu-renderer-error.ts';
import { requireLinearRgbaImage, type LinearRgbaImage } from '../../io/images/linear-image.ts';

/** Validates that both images are RGBA float of the same size with finite RGB; returns the pixel count. */
export function requireComparable(test: LinearRgbaImage, reference: LinearRgbaImage): number {
  const pixels = requireLinearRgbaImage(test, 'test');
  requireLinearRgbaImage(reference, 'reference');
  if (test.width !== reference.width || test.height !== reference.height) {
    throw new GpuRendererError('INVALID_OPTION', `expected ${reference.width}x${reference.height} like the reference, got ${test.width}x${test.height}`, {
      field: 'test',
    });
  }
  for (const [name, image] of [
    ['test', test],
    ['reference', reference],
  ] as const) {
    for (let i = 0; i < image.data.length; i++) {
      if (i % 4 !== 3 && !Number.isFinite(image.data[i])) {
        throw new GpuRendererError('INVALID_OPTION', `non-finite value ${image.data[i]} at pixel ${i >> 2}`, { field: `${name}.data` });
      }
    }
  }
  return pixels;
}

/** Mean squared error: mean over pixels and RGB of (test - reference)^2. */
export function meanSquaredError(test: LinearRgbaImage, reference: LinearRgbaImage): number {
  const pixels = requireComparable(test, reference);
  let sum = 0;
  for (let i = 0; i < pixels * 4; i++) {
    if (i % 4 === 3) continue;
    const d = test.data[i] - reference.data[i];
    sum += d * d;
  }
  return sum / (3 * pixels);
}

/** Root mean squared error, in the images' units (linear radiance). */
export function rootMeanSquaredError(test: LinearRgbaImage, reference: LinearRgbaImage): number {
  return Math.sqrt(meanSquaredError(test, reference));
}

function requirePositive(value: unknown, field: string): number {
  if (typeof value !== 'number' || !Number.isFinite(value) || value <= 0) {
    throw new GpuRendererError('INVALID_OPTION', `expected a finite number > 0, got ${String(value)}`, { field });
  }
  return value;
}

/**
 * Peak signal-to-noise ratio in dB, 10 log10(peak^2 / MSE), on linear radiance. Linear radiance has
 * no natural maximum, so the peak is required (e.g. the white level the comparison cares about, or
 * the reference's maximum); +Infinity for identical images.
 */
export function peakSignalToNoiseRatio(test: LinearRgbaImage, reference: LinearRgbaImage, options: { peak: number }): number {
  const peak = requirePositive(options?.peak, 'peak');
  const mse = meanSquaredError(test, reference);
  return mse === 0 ? Infinity : 10 * Math.log10((peak * peak) / mse);
}

/**
 * Relative MSE, mean over pixels and RGB of (test - reference)^2 / (reference^2 + epsilon): the
 * scale-free error of the Monte Carlo denoising and adaptive sampling literature (e.g. Rousselle,
 * Knaus and Zwicker 2011), with epsilon (default 0.01) keeping near-black pixels from dominating.
 */
export function relativeMeanSquaredError(test: LinearRgbaImage, reference: LinearRgbaImage, options: { epsilon?: number } = {}): number {
  const epsilon = requirePositive(options.epsilon ?? 0.01, 'epsilon');
  const pixels = requireComparable(test, reference);
  let sum = 0;
  for (let i = 0; i < pixels * 4; i++) {
    if (i % 4 === 3) continue;
    const r = reference.data[i];
    const d = test.data[i] - r;
    sum += (d * d) / (r * r + epsilon);
  }
  return sum / (3 * pixels);
}
