// Shared fixtures for the lighting tests: deterministic maps, direction helpers and the chi-square
// statistics of the BSDF harness.
import { rng } from '../helpers/random.ts';
import type { EnvironmentMap } from '../../src/lighting/environment-map.ts';

export { rng };
export { chiSquareTest, chiSquarePValue } from '../materials/bsdf-harness.ts';

/** Float32 RGBA map whose texels come from `f(i, j)` (alpha 1), wrapped as a validated map. */
export function makeMap(width: number, height: number, f: (i: number, j: number) => readonly number[], intensity = 1, rotationRadians = 0): EnvironmentMap {
  const data = new Float32Array(width * height * 4);
  for (let j = 0; j < height; j++) {
    for (let i = 0; i < width; i++) {
      const c = f(i, j);
      data.set([c[0]!, c[1]!, c[2]!, 1], 4 * (j * width + i));
    }
  }
  return { width, height, data, intensity, rotationRadians };
}

/** Uniform direction on the unit sphere. */
export function uniformSphere(random: () => number): [number, number, number] {
  const z = 1 - 2 * random();
  const r = Math.sqrt(Math.max(0, 1 - z * z));
  const phi = 2 * Math.PI * random();
  return [r * Math.cos(phi), r * Math.sin(phi), z];
}

/** Relative difference |a - b| / max(|a|, |b|, tiny). */
export function relDiff(a: number, b: number): number {
  return Math.abs(a - b) / Math.max(Math.abs(a), Math.abs(b), 1e-300);
}

/** Mean and standard error of a list of estimates. */
export function meanAndError(values: ArrayLike<number>): { mean: number; stderr: number } {
  let s = 0;
  let s2 = 0;
  for (let i = 0; i < values.length; i++) {
    s += values[i]!;
    s2 += values[i]! * values[i]!;
  }
  const n = values.length;
  const mean = s / n;
  const variance = Math.max(0, s2 / n - mean * mean);
  return { mean, stderr: Math.sqrt(variance / n) };
}
