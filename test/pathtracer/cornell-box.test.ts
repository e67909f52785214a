// Statistical tests on the built-in Cornell box: independent seeds agree within their standard
// error; the image is free of NaN/Inf/negative values; progressive frames equal one render of the
// same samples for the same seed, and agree statistically for another seed.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import { createCornellBoxScene } from '../../src/scene/cornell-box.ts';
import { testDevice } from '../helpers/gpu.ts';
import { meanDifferenceZ } from '../helpers/image-stats.ts';

const size = 40;

async function render(seed: number, frames: number, sppPerFrame: number): Promise<Float32Array> {
  const device = await testDevice();
  const scene = createCornellBoxScene();
  const renderer = await createWavefrontPathTracingComputeRenderer({
    device, width: size, height: size, maxDepth: 8, samplesPerPixel: sppPerFrame, seed, tileSize: 32,
    meshes: scene.meshes, camera: scene.camera, ...(scene.environment ? { environment: scene.environment } : {}),
  });
  try {
    for (let f = 0; f < frames; f++) {
      const stats = await renderer.renderFrame();
      assert.equal(stats.invalidSamples, 0, 'no sample may be NaN, Inf or negative');
      assert.equal(stats.samplesAccumulated, (f + 1) * sppPerFrame);
      assert.equal(stats.rays.camera, size * size * sppPerFrame);
      // Inside the closed box nearly every camera path scatters: the GPU-driven bounces really ran.
      assert.ok(stats.rays.extension > stats.rays.camera && stats.rays.shadow > 0.5 * stats.rays.camera, JSON.stringify(stats.rays));
    }
    return (await renderer.readRadiance()).data;
  } finally {
    renderer.destroy();
  }
}

test('Cornell box: two seeds agree within their standard error, with finite non-negative pixels', async () => {
  const a = await render(1, 1, 16);
  const b = await render(2, 1, 16);
  for (const v of [...a, ...b]) assert.ok(Number.isFinite(v) && v >= 0);
  const z = meanDifferenceZ(a, b);
  z.forEach((zc, c) => assert.ok(Math.abs(zc) < 4, `channel ${c}: z = ${zc}`));
  // The two images must really differ (independent noise) and not be black.
  let diff = 0, lum = 0;
  for (let i = 0; i < a.length; i += 4) { diff += Math.abs(a[i]! - b[i]!); lum += a[i]!; }
  assert.ok(diff > 0 && lum / (a.length / 4) > 0.05);
});

test('Cornell box: 4 progressive frames of 4 spp equal one 16 spp render (same seed) and agree statistically (other seed)', async () => {
  const progressive = await render(5, 4, 4);
  const single = await render(5, 1, 16);
  for (let i = 0; i < progressive.length; i++) {
    assert.ok(Math.abs(progressive[i]! - single[i]!) <= 1e-5 * Math.max(1, single[i]!), `pixel value ${i}: ${progressive[i]} vs ${single[i]}`);
  }
  const other = await render(6, 1, 16);
  meanDifferenceZ(progressive, other).forEach((zc, c) => assert.ok(Math.abs(zc) < 4, `channel ${c}: z = ${zc}`));
});

test('Cornell box: the mean radiance converges (a 64 spp render agrees with the 16 spp mean within noise)', async () => {
  const low = await render(11, 1, 16);
  const high = await render(12, 1, 64);
  meanDifferenceZ(low, high).forEach((zc, c) => assert.ok(Math.abs(zc) < 4, `channel ${c}: z = ${zc}`));
});
