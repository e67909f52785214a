import { test } from 'node:test';
import assert from 'node:assert/strict';
import { ssimMap, ssimRgba8, structuralSimilarity } from '../../../src/film/metrics/ssim.ts';
import { displayStructuralSimilarity } from '../../../src/film/metrics/display.ts';
import { GpuRendererError } from '../../../src/errors/gpu-renderer-error.ts';
import { rng } from '../../helpers/random.ts';

const C1 = (0.01 * 255) ** 2;
const C2 = (0.03 * 255) ** 2;
const gray = (width: number, height: number, f: (x: number, y: number) => number) => {
  const data = new Float64Array(width * height);
  for (let y = 0; y < height; y++) for (let x = 0; x < width; x++) data[y * width + x] = f(x, y);
  return { width, height, data };
};
const gaussian = (rand: () => number) => Math.sqrt(-2 * Math.log(1 - rand())) * Math.cos(2 * Math.PI * rand());

/** Brute-force SSIM straight from eq. 13-17 of Wang et al. 2004, with a full 2D window per pixel. */
function bruteForceMssim(a: { width: number; height: number; data: Float64Array }, b: typeof a): number {
  const w = new Float64Array(121);
  let s = 0;
  for (let i = 0; i < 11; i++) for (let j = 0; j < 11; j++) s += w[i * 11 + j] = Math.exp(-((i - 5) ** 2 + (j - 5) ** 2) / (2 * 1.5 * 1.5));
  for (let k = 0; k < 121; k++) w[k] /= s;
  let total = 0;
  let count = 0;
  for (let y = 0; y + 11 <= a.height; y++) {
    for (let x = 0; x + 11 <= a.width; x++) {
      let mx = 0;
      let my = 0;
      for (let i = 0; i < 11; i++) for (let j = 0; j < 11; j++) {
        mx += w[i * 11 + j] * a.data[(y + i) * a.width + x + j];
        my += w[i * 11 + j] * b.data[(y + i) * a.width + x + j];
      }
      let vx = 0;
      let vy = 0;
      let cxy = 0;
      for (let i = 0; i < 11; i++) for (let j = 0; j < 11; j++) {
        const dx = a.data[(y + i) * a.width + x + j] - mx;
        const dy = b.data[(y + i) * a.width + x + j] - my;
        vx += w[i * 11 + j] * dx * dx;
        vy += w[i * 11 + j] * dy * dy;
        cxy += w[i * 11 + j] * dx * dy;
      }
      total += ((2 * mx * my + C1) * (2 * cxy + C2)) / ((mx * mx + my * my + C1) * (vx + vy + C2));
      count++;
    }
  }
  return total / count;
}

test('identical images have SSIM 1; the map covers only windows inside the image', () => {
  const rand = rng(1);
  const a = gray(30, 20, () => 255 * rand());
  assert.ok(Math.abs(structuralSimilarity(a, a) - 1) < 1e-12);
  const map = ssimMap(a, a);
  assert.deepEqual([map.width, map.height], [20, 10]);
});

test('constant images a and a + d: SSIM is the luminance term (2a(a+d) + C1) / (a^2 + (a+d)^2 + C1)', () => {
  for (const [a, d] of [
    [100, 10],
    [20, 60],
    [0, 255],
  ]) {
    const expected = (2 * a * (a + d) + C1) / (a * a + (a + d) ** 2 + C1);
    const got = structuralSimilarity(gray(16, 16, () => a + d), gray(16, 16, () => a));
    assert.ok(Math.abs(got - expected) < 1e-12, `a ${a} d ${d}: ${got} vs ${expected}`);
  }
});

test('equals a brute-force evaluation of the paper (2D window, two-pass variance) on random structured images', () => {
  const rand = rng(2);
  const a = gray(27, 23, (x, y) => 128 + 60 * Math.sin(x * 0.7) * Math.cos(y * 0.4) + 20 * rand());
  const b = gray(27, 23, (x, y) => 0.8 * a.data[y * 27 + x] + 30 * rand());
  const got = structuralSimilarity(b, a);
  const want = bruteForceMssim(b, a);
  assert.ok(Math.abs(got - want) < 1e-10, `${got} vs ${want}`);
  // SSIM is symmetric in its arguments; inverting the structure makes it negative.
  assert.ok(Math.abs(structuralSimilarity(a, b) - got) < 1e-12);
  const inverted = gray(27, 23, (x, y) => 255 - a.data[y * 27 + x]);
  assert.ok(structuralSimilarity(inverted, a) < 0);
});

test('white noise of known variance on a flat image: SSIM near C2 / (sigma^2 (1 - sum w^2) + C2)', () => {
  // Over a flat reference, mean and covariance terms vanish and SSIM = l * C2 / (s^2 + C2), where
  // s^2 is the window-weighted sample variance with E[s^2] = sigma^2 (1 - sum of squared weights).
  // Jensen's inequality puts the mean slightly above the value at E[s^2] (about +0.01 here).
  const rand = rng(4);
  const sigma = 10;
  const flat = gray(96, 96, () => 128);
  const noisy = gray(96, 96, () => 128 + sigma * gaussian(rand));
  let sumW2 = 0;
  const w1 = Array.from({ length: 11 }, (_, i) => Math.exp(-((i - 5) ** 2) / (2 * 1.5 * 1.5)));
  const s = w1.reduce((p, v) => p + v, 0);
  for (const wi of w1) for (const wj of w1) sumW2 += ((wi * wj) / (s * s)) ** 2;
  const expected = C2 / (sigma * sigma * (1 - sumW2) + C2);
  const got = structuralSimilarity(noisy, flat);
  assert.ok(got > expected - 0.005 && got < expected + 0.03, `${got} vs ${expected}`);
  // More noise, lower SSIM.
  const noisier = gray(96, 96, () => 128 + 3 * sigma * gaussian(rand));
  assert.ok(structuralSimilarity(noisier, flat) < got / 3);
});

test('RGBA8 and display SSIM work on luma; errors are typed', () => {
  const width = 16;
  const height = 12;
  const rgba = new Uint8ClampedArray(width * height * 4).map((_, i) => (i % 4 === 3 ? 255 : (i * 31) % 256));
  assert.ok(Math.abs(ssimRgba8({ width, height, data: rgba }, { width, height, data: rgba }) - 1) < 1e-12);
  const radiance = new Float32Array(width * height * 4).map((_, i) => (i % 4 === 3 ? 1 : ((i * 7) % 11) / 10));
  assert.ok(Math.abs(displayStructuralSimilarity({ width, height, data: radiance }, { width, height, data: radiance }, { toneMapping: 'agx' }) - 1) < 1e-12);
  const darker = radiance.map((v, i) => (i % 4 === 3 ? v : v * 0.5));
  assert.ok(displayStructuralSimilarity({ width, height, data: darker }, { width, height, data: radiance }) < 0.99);
  const isField = (field: string) => (e: unknown) => e instanceof GpuRendererError && e.field === field;
  assert.throws(() => structuralSimilarity(gray(10, 20, () => 0), gray(10, 20, () => 0)), isField('test'));
  assert.throws(() => structuralSimilarity(gray(12, 12, () => 0), gray(13, 12, () => 0)), isField('test'));
  assert.throws(() => structuralSimilarity(gray(12, 12, () => 0), gray(12, 12, () => 0), { dynamicRange: 0 }), isField('dynamicRange'));
});
