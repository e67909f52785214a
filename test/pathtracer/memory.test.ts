// Queues are sized by tile: the path-state memory of a 3840x2160 renderer equals that of a
// 1280x720 one; only the per-pixel accumulation and display buffers scale with resolution.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import { createCornellBoxScene } from '../../src/scene/cornell-box.ts';
import { testDevice } from '../helpers/gpu.ts';

test('wavefront queue memory does not grow with output resolution', async () => {
  const device = await testDevice();
  const scene = createCornellBoxScene();
  const snapshots = [];
  for (const [width, height] of [[1280, 720], [3840, 2160]] as const) {
    const renderer = await createWavefrontPathTracingComputeRenderer({ device, width, height, tileSize: 256, meshes: scene.meshes, camera: scene.camera });
    snapshots.push(renderer.getSnapshot().memory);
    renderer.destroy();
  }
  const [hd, uhd] = snapshots as [(typeof snapshots)[0], (typeof snapshots)[0]];
  assert.equal(uhd.queueBytes, hd.queueBytes);
  assert.equal(uhd.sceneBytes, hd.sceneBytes);
  // Per-pixel buffers: 16 B float32 accumulation + 4 B display per pixel, plus small constants.
  assert.ok(Math.abs(uhd.frameBytes - hd.frameBytes - (3840 * 2160 - 1280 * 720) * 20) < 1024);
});
