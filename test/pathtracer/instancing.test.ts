// Two-level acceleration (pathtracer/scene/instancing.ts): placements traced through bottom-level
// trees render what the same placements flattened into world-space triangles render, under
// rotations, non-uniform and mirroring scales, single-sided and alpha-masked materials, material
// overrides and emissive placements (each its own light). Same seed: the same paths, so the pixels
// agree to float rounding (object-space intersection rounds differently); other seeds: agreement
// within the standard error.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import type { InstancingMode, WavefrontPathTracingOptions, WavefrontRendererSnapshot } from '../../src/index.ts';
import { testDevice } from '../helpers/gpu.ts';
import { meanDifferenceZ } from '../helpers/image-stats.ts';
import { transformsCamera, transformsScene } from './instancing-scenes.ts';

const SIZE = 48;

async function render(instancing: InstancingMode, seed: number, spp: number, extra: Partial<WavefrontPathTracingOptions> = {}): Promise<{ image: Float32Array; stats: WavefrontRendererSnapshot }> {
  const device = await testDevice();
  const renderer = await createWavefrontPathTracingComputeRenderer({
    device, width: SIZE, height: SIZE, maxDepth: 4, samplesPerPixel: spp, seed, instancing,
    ...transformsScene(), camera: transformsCamera, environment: { color: [0.15, 0.17, 0.2] }, ...extra,
  });
  try {
    const frame = await renderer.renderFrame();
    assert.equal(frame.invalidSamples, 0);
    return { image: (await renderer.readRadiance()).data, stats: renderer.getSnapshot() };
  } finally {
    renderer.destroy();
  }
}

test('placements through bottom levels render the flattened image: same seed to rounding, other seeds within noise', async () => {
  const flat = await render('off', 3, 16);
  const shared = await render('always', 3, 16);
  assert.equal(flat.stats.instancing.placements, 0);
  assert.equal(shared.stats.instancing.placements, 12);
  // Ground, sphere, single-sided wedge, the card under two materials, the panel.
  assert.equal(shared.stats.instancing.sharedMeshes, 6);
  assert.equal(shared.stats.instancing.topLevelRecords, 12);
  let sum = 0, diff = 0, far = 0;
  for (let i = 0; i < flat.image.length; i += 4) {
    for (let c = 0; c < 3; c++) {
      const a = flat.image[i + c]!, b = shared.image[i + c]!;
      sum += a;
      diff += Math.abs(a - b);
      if (Math.abs(a - b) > 0.05 * Math.max(a, b) + 1e-3) far++;
    }
  }
  const pixels = (3 * flat.image.length) / 4;
  assert.ok(diff / sum < 0.02, `relative L1 difference ${(diff / sum).toFixed(4)} at the same seed`);
  assert.ok(far < 0.03 * pixels, `${far} of ${pixels} channel values differ by more than 5%`);
  const other = await render('always', 11, 16);
  const z = meanDifferenceZ(flat.image, other.image);
  assert.ok(z.every((v) => Math.abs(v) < 4), `mean difference z = ${z.map((v) => v.toFixed(2)).join(', ')}`);
});
