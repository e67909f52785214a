// Block-by-block comparison of a render against a stored independent reference (Mitsuba 3; the
// scripts under scripts/reference/ write the JSON): per-block statistics of our render, and the
// Bonferroni z tests of the reference tests (test/materials/glass-sphere-reference.test.ts,
// test/accel/instanced-transforms-reference.test.ts).
//
// Statistics: for every block b and channel c, z = (ours - ref) / sqrt(se_ours^2 + se_ref^2),
// se_ours from the renderer's per-pixel variance of the mean (the iid estimate, which for
// Owen-scrambled Sobol samples is typically conservative). Under equal expectations z is about
// standard normal: with a family-wise false-alarm rate of 1e-3 over the 3 B two-sided tests
// (Bonferroni), every |z| must stay below Phi^-1(1 - 1e-3 / (6 B)) (4.84 for B = 256 blocks). The
// whole image's mean per channel likewise, at 1e-3 over its 3 tests (3.59).
import assert from 'node:assert/strict';
import type { TestContext } from 'node:test';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import type { WavefrontPathTracingOptions } from '../../src/pathtracer/types.ts';

export type Vec3 = [number, number, number];

/** Image size and block edge (both dimensions multiples of it). */
export interface BlockGrid { width: number; height: number; block: number }

/** Per block (row-major from the top-left) and channel: mean radiance and its standard error; the whole image's too. */
export interface BlockStats {
  mean: Vec3[];
  standardError: Vec3[];
  imageMean: Vec3;
  imageStandardError: Vec3;
}

/** What the reference scripts store (mitsuba-reference.json). */
export interface BlockReference extends BlockStats {
  matchesMaxDepth: number;
  blocksX: number;
  blocksY: number;
  samplesPerPixel: number;
}

/**
 * Block statistics from per-pixel means and variances of the mean (readAov('variance')): pixels
 * are independent, so a block's variance is the sum of its pixels' over n^2.
 */
export function blockStats(grid: BlockGrid, mean: Float32Array, variance: Float32Array): BlockStats {
  const { width, height, block } = grid;
  const n = block * block;
  const out: BlockStats = { mean: [], standardError: [], imageMean: [0, 0, 0], imageStandardError: [0, 0, 0] };
  const imageVariance: Vec3 = [0, 0, 0];
  for (let j = 0; j < height / block; j++) {
    for (let i = 0; i < width / block; i++) {
      const m: Vec3 = [0, 0, 0], v: Vec3 = [0, 0, 0];
      for (let y = j * block; y < (j + 1) * block; y++) {
        for (let x = i * block; x < (i + 1) * block; x++) {
          for (let c = 0; c < 3; c++) { m[c] += mean[4 * (y * width + x) + c]!; v[c] += variance[4 * (y * width + x) + c]!; }
        }
      }
      out.mean.push(m.map((s) => s / n) as Vec3);
      out.standardError.push(v.map((s) => Math.sqrt(s) / n) as Vec3);
      for (let c = 0; c < 3; c++) { out.imageMean[c] += m[c]! / (width * height); imageVariance[c] += v[c]!; }
    }
  }
  out.imageStandardError = imageVariance.map((s) => Math.sqrt(s) / (width * height)) as Vec3;
  return out;
}

/** Renders one frame with AOVs on (for the variance) and returns its block statistics. */
export async function renderBlockStats(grid: BlockGrid, options: Omit<WavefrontPathTracingOptions, 'width' | 'height' | 'aovs'>): Promise<BlockStats & { invalidSamples: number }> {
  const renderer = await createWavefrontPathTracingComputeRenderer({ ...options, width: grid.width, height: grid.height, aovs: true });
  try {
    const stats = await renderer.renderFrame();
    const stat = blockStats(grid, (await renderer.readRadiance()).data, (await renderer.readAov('variance')).data);
    return { ...stat, invalidSamples: stats.invalidSamples };
  } finally {
    renderer.destroy();
  }
}

/** Phi^-1(1 - p) for small p (Abramowitz & Stegun 26.2.23, |error| < 4.5e-4). */
export function upperNormalQuantile(p: number): number {
  const t = Math.sqrt(-2 * Math.log(p));
  return t - (2.515517 + 0.802853 * t + 0.010328 * t * t) / (1 + 1.432788 * t + 0.189269 * t * t + 0.001308 * t * t * t);
}

// Blocks that both renderers see without noise (a black sky) must agree exactly: z 0 or infinite.
function z(difference: number, se: number): number {
  return se > 0 ? difference / se : difference === 0 ? 0 : Infinity;
}

export interface BlockComparison {
  /** Per block and channel. */
  z: Vec3[];
  worst: number;
  /** Blocks with some channel beyond 3.29 sigma (two-sided 1e-3 each), and of them those darker than the reference. */
  beyond329: number;
  darker329: number;
  /** The Bonferroni bounds of the blocks and of the image mean. */
  zBlock: number;
  zImage: number;
  zMean: Vec3;
}

export function compareBlocks(ours: BlockStats, reference: BlockStats): BlockComparison {
  const blocks = ours.mean.length;
  assert.equal(reference.mean.length, blocks, 'the reference has as many blocks');
  const zs = ours.mean.map((m, b) => m.map((v, c) => z(v - reference.mean[b]![c]!, Math.hypot(ours.standardError[b]![c]!, reference.standardError[b]![c]!))) as Vec3);
  return {
    z: zs,
    worst: Math.max(...zs.flat().map(Math.abs)),
    beyond329: zs.filter((zb) => zb.some((v) => Math.abs(v) > 3.29)).length,
    darker329: zs.filter((zb) => zb.some((v) => v < -3.29)).length,
    zBlock: upperNormalQuantile(1e-3 / (6 * blocks)),
    zImage: upperNormalQuantile(1e-3 / 6),
    zMean: ours.imageMean.map((v, c) => z(v - reference.imageMean[c]!, Math.hypot(ours.imageStandardError[c]!, reference.imageStandardError[c]!))) as Vec3,
  };
}

/**
 * Compares, reports (test diagnostics: blocks beyond 3.29 sigma and beyond the Bonferroni bound,
 * the worst |z|, the image means) and asserts every block and the image mean within their bounds.
 */
export function assertMatchesReference(t: TestContext, ours: BlockStats, reference: BlockReference, spp: number): BlockComparison {
  const r = compareBlocks(ours, reference);
  const blocks = ours.mean.length;
  const beyondBound = r.z.filter((zb) => zb.some((v) => Math.abs(v) > r.zBlock)).length;
  t.diagnostic(`${spp} spp against Mitsuba's ${reference.samplesPerPixel}: blocks beyond 3.29 sigma ${r.beyond329} of ${blocks} (${r.darker329} darker), beyond ${r.zBlock.toFixed(2)} sigma ${beyondBound}; worst |z| ${r.worst.toFixed(2)}`);
  t.diagnostic(`image mean ours ${ours.imageMean.map((v) => v.toFixed(5)).join(' ')} vs ${reference.imageMean.map((v) => v.toFixed(5)).join(' ')}, z ${r.zMean.map((v) => v.toFixed(2)).join(' ')}`);
  assert.ok(r.worst < r.zBlock, `a block differs beyond ${r.zBlock.toFixed(2)} sigma: worst |z| = ${r.worst.toFixed(2)}`);
  for (const v of r.zMean) assert.ok(Math.abs(v) < r.zImage, `the image mean differs beyond ${r.zImage.toFixed(2)} sigma: z = ${r.zMean.map((x) => x.toFixed(2)).join(' ')}`);
  return r;
}
