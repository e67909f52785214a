import { adaptiveConvergedMask } from '../../../src/film/adaptive/converged-mask.ts';
import { rng } from '../../helpers/random.ts';

export interface Simulation {
  width: number;
  height: number;
  samples: Uint32Array;
  estimate: Float64Array;
  /** Mean of each pixel's own samples, recomputed from the raw sample log. */
  sampleMean: Float64Array;
}

/**
 * Progressive adaptive rendering of a synthetic image: each pixel's samples come from `draw(x, rand)`
 * (the same value in R, G and B); every `step` samples the convergence mask decides which pixels get
 * the next batch, up to `maxSamples`, as Cycles' scheduler does. `half` accumulates the even-indexed
 * samples.
 */
export function simulateAdaptive(options: {
  width: number;
  height: number;
  seed: number;
  draw: (x: number, rand: () => number) => number;
  threshold: number;
  minimumSamplesPerPixel: number;
  step: number;
  maxSamples: number;
}): Simulation {
  const { width, height, draw, step } = options;
  const n = width * height;
  const rand = rng(options.seed);
  const sum = new Float64Array(n);
  const sumEven = new Float64Array(n);
  const samples = new Uint32Array(n);
  const log: number[][] = Array.from({ length: n }, () => []);
  let active = new Uint8Array(n).fill(1);
  for (let round = 0; round * step < options.maxSamples; round++) {
    for (let p = 0; p < n; p++) {
      if (!active[p]) continue;
      for (let k = 0; k < step; k++) {
        const v = draw(p % width, rand);
        if (samples[p] % 2 === 0) sumEven[p] += v;
        sum[p] += v;
        samples[p]++;
        log[p].push(v);
      }
    }
    const full = new Float32Array(4 * n);
    const half = new Float32Array(4 * n);
    for (let p = 0; p < n; p++) {
      const mean = sum[p] / samples[p];
      const meanEven = sumEven[p] / Math.ceil(samples[p] / 2);
      full.set([mean, mean, mean, 1], 4 * p);
      half.set([meanEven, meanEven, meanEven, 1], 4 * p);
    }
    const mask = adaptiveConvergedMask({ width, height, data: full }, { width, height, data: half }, samples, options);
    if (mask.activePixels === 0) break;
    active = mask.converged.map((c) => 1 - c);
  }
  const estimate = sum.map((s, p) => s / samples[p]);
  const sampleMean = Float64Array.from(log, (values) => values.reduce((a, b) => a + b, 0) / values.length);
  return { width, height, samples, estimate, sampleMean };
}
