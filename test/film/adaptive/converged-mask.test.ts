import { test } from 'node:test';
import assert from 'node:assert/strict';
import {
  adaptiveConvergedMask,
  adaptiveSamplingError,
  defaultAdaptiveSamplingParameters,
} from '../../../src/film/adaptive/converged-mask.ts';
import { GpuRendererError } from '../../../src/errors/gpu-renderer-error.ts';
import { simulateAdaptive } from './simulate.ts';

const rgba = (width: number, height: number, rgb: (p: number) => [number, number, number]) => {
  const data = new Float32Array(width * height * 4);
  for (let p = 0; p < width * height; p++) data.set([...rgb(p), 1], 4 * p);
  return { width, height, data };
};

test('the per-pixel error is sum |I - A| / (1e-4 + sqrt(sum I)) below intensity 1 and / (1e-4 + sum I) above', () => {
  // Dim pixel: sum I = 0.3 < 1.
  assert.ok(Math.abs(adaptiveSamplingError(0.1, 0.1, 0.1, 0.12, 0.1, 0.07) - 0.05 / (1e-4 + Math.sqrt(0.3))) < 1e-12);
  // Bright pixel: sum I = 3 >= 1 normalises by the intensity itself.
  assert.ok(Math.abs(adaptiveSamplingError(1, 1, 1, 1.1, 0.9, 1) - 0.2 / (1e-4 + 3)) < 1e-12);
  assert.equal(adaptiveSamplingError(0, 0, 0, 0, 0, 0), 0);
  // Mask on one pixel, either side of the threshold.
  const full = rgba(1, 1, () => [0.1, 0.1, 0.1]);
  const half = rgba(1, 1, () => [0.12, 0.1, 0.07]);
  const e = 0.05 / (1e-4 + Math.sqrt(0.3));
  assert.equal(adaptiveConvergedMask(full, half, 8, { threshold: e * 1.001 }).converged[0], 1);
  assert.equal(adaptiveConvergedMask(full, half, 8, { threshold: e * 0.999 }).converged[0], 0);
  // Exposure scales both estimates before the test, as Cycles' film exposure does.
  const scaled = adaptiveConvergedMask(full, half, 8, { threshold: 1, exposure: 4 }).error[0];
  assert.ok(Math.abs(scaled - adaptiveSamplingError(0.4, 0.4, 0.4, 0.48, 0.4, 0.28)) < 1e-6);
});

test('below the minimum sample count nothing converges, whatever the error', () => {
  const flat = rgba(6, 4, () => [0.5, 0.5, 0.5]);
  const below = adaptiveConvergedMask(flat, flat, 15, { threshold: 0.01, minimumSamplesPerPixel: 16 });
  assert.equal(below.activePixels, 24);
  assert.ok(below.error.every((e) => e === Infinity));
  assert.equal(adaptiveConvergedMask(flat, flat, 16, { threshold: 0.01, minimumSamplesPerPixel: 16 }).activePixels, 0);
  // Per-pixel counts: only the pixel under the minimum (and its 3x3 neighbourhood) keeps sampling.
  const counts = new Uint32Array(24).fill(32);
  counts[0] = 3;
  const mask = adaptiveConvergedMask(flat, flat, counts, { threshold: 0.01, minimumSamplesPerPixel: 16 });
  assert.deepEqual([...mask.converged], [0, 0, 1, 1, 1, 1, 0, 0, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1]);
});

test('one unconverged pixel keeps exactly its 3x3 neighbourhood sampling (Cycles filter_x then filter_y)', () => {
  const width = 7;
  const height = 5;
  const full = rgba(width, height, () => [0.5, 0.5, 0.5]);
  for (const [cx, cy] of [
    [3, 2],
    [0, 0],
    [6, 4],
    [6, 0],
  ]) {
    const half = rgba(width, height, (p) => (p === cy * width + cx ? [0.9, 0.5, 0.5] : [0.5, 0.5, 0.5]));
    const mask = adaptiveConvergedMask(full, half, 64, { threshold: 0.01 });
    for (let y = 0; y < height; y++) {
      for (let x = 0; x < width; x++) {
        const inside = Math.abs(x - cx) <= 1 && Math.abs(y - cy) <= 1;
        assert.equal(mask.converged[y * width + x], inside ? 0 : 1, `centre ${cx},${cy} pixel ${x},${y}`);
      }
    }
  }
  // NaN estimates never count as converged.
  const nan = rgba(3, 3, (p) => (p === 4 ? [Number.NaN, 0, 0] : [0.5, 0.5, 0.5]));
  assert.equal(adaptiveConvergedMask(nan, nan, 64, { threshold: 0.01 }).activePixels, 9);
});

test('progressive rendering: noisy pixels keep sampling, quiet ones stop at the minimum, estimates stay sample means', () => {
  // Left half: 0.5 with tiny uniform noise; right half: exponential samples with mean 0.5 (sd 0.5).
  const draw = (x: number, rand: () => number) => (x < 16 ? 0.5 + 0.01 * (rand() - 0.5) : -0.5 * Math.log(1 - rand()));
  let sum = 0;
  let variance = 0;
  let count = 0;
  for (let seed = 1; seed <= 4; seed++) {
    const sim = simulateAdaptive({ width: 32, height: 16, seed, draw, threshold: 0.05, minimumSamplesPerPixel: 16, step: 16, maxSamples: 2048 });
    let quiet = 0;
    let noisy = 0;
    for (let p = 0; p < 32 * 16; p++) {
      const x = p % 32;
      // The estimate is exactly the mean of the samples the pixel received: nothing is reweighted.
      assert.ok(Math.abs(sim.estimate[p] - sim.sampleMean[p]) < 1e-12);
      if (x < 15) {
        assert.equal(sim.samples[p], 16, `quiet pixel ${p} took ${sim.samples[p]} samples`);
        quiet += sim.samples[p];
      } else if (x === 15) {
        // Next to the noisy half: the 3x3 dilation keeps it sampling.
        assert.ok(sim.samples[p] > 16);
      } else {
        noisy += sim.samples[p];
        sum += sim.estimate[p];
        variance += 0.25 / sim.samples[p];
        count++;
      }
    }
    assert.ok(noisy / (16 * 16) > 20 * (quiet / (15 * 16)), `noisy ${noisy / 256} vs quiet ${quiet / 240} samples per pixel`);
  }
  // The average estimate over the noisy pixels matches the true mean 0.5 within 4 standard errors
  // (SE from each pixel's variance 0.25 / n): stopping adds no measurable bias here.
  const standardError = Math.sqrt(variance) / count;
  assert.ok(Math.abs(sum / count - 0.5) < 4 * standardError, `mean ${sum / count}, SE ${standardError}`);
});

test("Cycles' automatic parameters and typed errors", () => {
  assert.deepEqual(defaultAdaptiveSamplingParameters(10), { threshold: 0.1, minimumSamplesPerPixel: 32 });
  assert.deepEqual(defaultAdaptiveSamplingParameters(100), { threshold: 0.01, minimumSamplesPerPixel: 64 });
  assert.deepEqual(defaultAdaptiveSamplingParameters(4096), { threshold: 0.001, minimumSamplesPerPixel: 128 });
  assert.equal(defaultAdaptiveSamplingParameters(4096, 0.5).minimumSamplesPerPixel, 20);
  const img = rgba(2, 2, () => [0, 0, 0]);
  const isField = (field: string) => (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_OPTION' && e.field === field;
  assert.throws(() => adaptiveConvergedMask(img, img, 4, { threshold: 0 }), isField('threshold'));
  assert.throws(() => adaptiveConvergedMask(img, img, 4, {} as never), isField('threshold'));
  assert.throws(() => adaptiveConvergedMask(img, img, -1, { threshold: 0.1 }), isField('samples'));
  assert.throws(() => adaptiveConvergedMask(img, img, new Uint32Array(3), { threshold: 0.1 }), isField('samples'));
  assert.throws(() => adaptiveConvergedMask(img, rgba(1, 2, () => [0, 0, 0]), 4, { threshold: 0.1 }), isField('half'));
  assert.throws(() => adaptiveConvergedMask(img, img, 4, { threshold: 0.1, minimumSamplesPerPixel: 1.5 }), isField('minimumSamplesPerPixel'));
  assert.throws(() => defaultAdaptiveSamplingParameters(0), isField('maxSamplesPerPixel'));
});
