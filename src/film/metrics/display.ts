/**
 * Metrics on what a viewer sees: both images go through the same display transform (exposure,
 * tone mapping, sRGB encoding, 8-bit quantisation: encodeRadianceToRgba8) before comparison.
 */
import { encodeRadianceToRgba8, type EncodeRadianceOptions } from '../tone-mapping.ts';
import type { LinearRgbaImage } from '../../io/images/linear-image.ts';
import { requireComparable } from './image-error.ts';
import { ssimRgba8 } from './ssim.ts';

/** PSNR in dB between the 8-bit sRGB display encodings (peak 255, RGB channels); +Infinity if equal. */
export function displayPeakSignalToNoiseRatio(test: LinearRgbaImage, reference: LinearRgbaImage, display: EncodeRadianceOptions = {}): number {
  requireComparable(test, reference);
  const a = encodeRadianceToRgba8(test.data, display);
  const b = encodeRadianceToRgba8(reference.data, display);
  let sum = 0;
  for (let i = 0; i < a.length; i++) {
    if (i % 4 === 3) continue;
    const d = a[i] - b[i];
    sum += d * d;
  }
  const mse = sum / ((a.length / 4) * 3);
  return mse === 0 ? Infinity : 10 * Math.log10((255 * 255) / mse);
}

/** Mean SSIM (ssimRgba8) of the 8-bit sRGB display encodings of two radiance images. */
export function displayStructuralSimilarity(test: LinearRgbaImage, reference: LinearRgbaImage, display: EncodeRadianceOptions = {}): number {
  requireComparable(test, reference);
  const { width, height } = reference;
  return ssimRgba8(
    { width, height, data: encodeRadianceToRgba8(test.data, display) },
    { width, height, data: encodeRadianceToRgba8(reference.data, display) },
  );
}
