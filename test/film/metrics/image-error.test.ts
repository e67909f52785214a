import { test } from 'node:test';
import assert from 'node:assert/strict';
import {
  meanSquaredError,
  peakSignalToNoiseRatio,
  relativeMeanSquaredError,
  rootMeanSquaredError,
} from '../../../src/film/metrics/image-error.ts';
import { displayPeakSignalToNoiseRatio } from '../../../src/film/metrics/display.ts';
import { srgbToLinear } from '../../../src/film/tone-mapping.ts';
import { GpuRendererError } from '../../../src/errors/gpu-renderer-error.ts';
import { rng } from '../../helpers/random.ts';

const size = 128;
function image(fill: (i: number) => number, width = size, height = size) {
  const data = new Float32Array(width * height * 4);
  for (let i = 0; i < data.length; i++) data[i] = i % 4 === 3 ? 1 : fill(i);
  return { width, height, data };
}
const gaussian = (rand: () => number) => Math.sqrt(-2 * Math.log(1 - rand())) * Math.cos(2 * Math.PI * rand());

test('identical images: zero error and infinite PSNR', () => {
  const a = image((i) => (i % 17) * 0.1);
  assert.equal(meanSquaredError(a, a), 0);
  assert.equal(rootMeanSquaredError(a, a), 0);
  assert.equal(relativeMeanSquaredError(a, a), 0);
  assert.equal(peakSignalToNoiseRatio(a, a, { peak: 1 }), Infinity);
  assert.equal(displayPeakSignalToNoiseRatio(a, a), Infinity);
});

test('a constant offset d gives MSE d^2, RMSE d, PSNR 20 log10(peak / d) and relMSE d^2 / (r^2 + eps)', () => {
  // Values exactly representable in float32 so the offset is exact.
  const reference = image(() => 0.5);
  const test = image(() => 0.625);
  const d = 0.125;
  assert.equal(meanSquaredError(test, reference), d * d);
  assert.equal(rootMeanSquaredError(test, reference), d);
  assert.ok(Math.abs(peakSignalToNoiseRatio(test, reference, { peak: 4 }) - 20 * Math.log10(4 / d)) < 1e-12);
  assert.ok(Math.abs(relativeMeanSquaredError(test, reference) / ((d * d) / (0.25 + 0.01)) - 1) < 1e-12);
  assert.ok(Math.abs(relativeMeanSquaredError(test, reference, { epsilon: 1 }) / ((d * d) / 1.25) - 1) < 1e-12);
  // Alpha is ignored.
  const alpha = image(() => 0.5);
  for (let i = 3; i < alpha.data.length; i += 4) alpha.data[i] = 0;
  assert.equal(meanSquaredError(alpha, reference), 0);
});

test('Gaussian noise of known sigma: PSNR matches 10 log10(peak^2 / sigma^2) within sampling error', () => {
  const rand = rng(3);
  const sigma = 0.05;
  const reference = image((i) => 0.2 + 0.6 * ((i >> 2) / (size * size)));
  const noisy = { ...reference, data: reference.data.map((v, i) => (i % 4 === 3 ? v : v + sigma * gaussian(rand))) };
  // N = 3 * 128^2 samples: the MSE's relative standard deviation is sqrt(2 / N) = 0.64%, i.e.
  // 0.028 dB; allow 4 standard deviations (0.11 dB).
  const expected = 10 * Math.log10(1 / (sigma * sigma));
  const psnr = peakSignalToNoiseRatio(noisy, reference, { peak: 1 });
  assert.ok(Math.abs(psnr - expected) < 0.11, `PSNR ${psnr} vs ${expected}`);
  assert.ok(Math.abs(rootMeanSquaredError(noisy, reference) / sigma - 1) < 0.013);
});

test('display PSNR compares 8-bit sRGB encodings: ten code values apart everywhere -> 20 log10(255 / 10)', () => {
  const reference = image(() => srgbToLinear(100 / 255));
  const test = image(() => srgbToLinear(110 / 255));
  const psnr = displayPeakSignalToNoiseRatio(test, reference, { toneMapping: 'linear' });
  assert.ok(Math.abs(psnr - 20 * Math.log10(255 / 10)) < 1e-12, `${psnr}`);
  // Exposure applies to both images: one stop down changes the code values, not the identity.
  assert.equal(displayPeakSignalToNoiseRatio(reference, reference, { exposureEv: -1 }), Infinity);
});

test('typed errors: size mismatch, non-finite values, missing or bad peak', () => {
  const a = image(() => 0.5);
  const b = image(() => 0.5, size, size - 1);
  const isField = (field: string) => (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_OPTION' && e.field === field;
  assert.throws(() => meanSquaredError(b, a), isField('test'));
  const nan = image(() => 0.5);
  nan.data[5] = Number.NaN;
  assert.throws(() => meanSquaredError(nan, a), isField('test.data'));
  assert.throws(() => meanSquaredError(a, nan), isField('reference.data'));
  assert.throws(() => peakSignalToNoiseRatio(a, a, { peak: 0 }), isField('peak'));
  assert.throws(() => peakSignalToNoiseRatio(a, a, undefined as never), isField('peak'));
  assert.throws(() => relativeMeanSquaredError(a, a, { epsilon: -1 }), isField('epsilon'));
});
