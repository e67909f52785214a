// A still of the animation path traced: the posed scene at time t (skinned vertices baked on the
// CPU, BVH built from them) rendered by the wavefront path tracer shows the character with the same
// silhouette as the raster preview of the same frame.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import { createAnimatedSceneRenderer } from '../../src/raster/index.ts';
import { ADVENTURE_BEATS, ADVENTURE_CAMERA, ADVENTURE_CLIPS, ADVENTURE_PROPS, ADVENTURE_ROUTE, adventureFigure, characterClass } from '../animation/fixtures/adventure-scene.ts';
import { testDevice } from '../helpers/gpu.ts';
import { maskOverlap } from './silhouette.ts';

const W = 80;
const H = 60;

test('the path-traced posed still and the raster preview show the same character silhouette', async () => {
  const device = await testDevice();
  const preview = await createAnimatedSceneRenderer({
    device, width: W, height: H, modelAsset: adventureFigure().document, clipAssets: ADVENTURE_CLIPS, beats: ADVENTURE_BEATS,
    route: ADVENTURE_ROUTE, props: ADVENTURE_PROPS, camera: ADVENTURE_CAMERA, shadow: false, lights: [], toneMapping: 'linear',
  });
  const tMs = 1600;
  await preview.renderOnce(tMs);
  const raster = await preview.readPixels();
  const scene = preview.posedScene(tMs);
  preview.destroy();
  const tracer = await createWavefrontPathTracingComputeRenderer({ ...scene, device, width: W, height: H, maxDepth: 2, samplesPerPixel: 16, toneMapping: 'linear' });
  await tracer.renderFrame();
  const traced = await tracer.readPixels();
  tracer.destroy();
  const mask = (data: ArrayLike<number>): Uint8Array => Uint8Array.from({ length: W * H }, (_, i) => (characterClass(data, i) > 0 ? 1 : 0));
  const overlap = maskOverlap(mask(raster.data), mask(traced.data));
  assert.ok(overlap.a > 60, `raster character ${overlap.a} px`);
  assert.ok(overlap.iou > 0.8, `silhouette IoU ${overlap.iou.toFixed(3)} (raster ${overlap.a} px, path traced ${overlap.b} px)`);
});

test('the posed still carries the raster view\'s lighting: its default key light and sky light the ground alike in both renderers', async () => {
  const device = await testDevice();
  const preview = await createAnimatedSceneRenderer({
    device, width: W, height: H, modelAsset: adventureFigure().document, clipAssets: ADVENTURE_CLIPS, beats: ADVENTURE_BEATS,
    route: ADVENTURE_ROUTE, props: ADVENTURE_PROPS, camera: ADVENTURE_CAMERA, shadow: false, toneMapping: 'linear', exposure: 0.25,
  });
  const tMs = 1600;
  await preview.renderOnce(tMs);
  const raster = await preview.readPixels();
  const scene = preview.posedScene(tMs);
  preview.destroy();
  assert.equal(scene.lights.length, 1, 'the default key light');
  assert.equal(scene.lights[0]!.type, 'directional');
  const tracer = await createWavefrontPathTracingComputeRenderer({ ...scene, device, width: W, height: H, maxDepth: 3, samplesPerPixel: 32, toneMapping: 'linear', exposure: 0.25 });
  await tracer.renderFrame();
  const traced = await tracer.readPixels();
  tracer.destroy();
  // The ground in the bottom rows, away from the character and props: direct light from the key
  // light and the uniform sky (the raster view's irradiance is exact for both on a flat ground).
  const ground = (data: ArrayLike<number>): number => {
    let sum = 0;
    let n = 0;
    for (let y = H - 6; y < H; y++) {
      for (let x = 0; x < W; x++) {
        const i = y * W + x;
        if (characterClass(raster.data, i) > 0 || characterClass(traced.data, i) > 0) continue;
        sum += data[4 * i]! + data[4 * i + 1]! + data[4 * i + 2]!;
        n++;
      }
    }
    return sum / n;
  };
  const r = ground(raster.data);
  const p = ground(traced.data);
  assert.ok(r > 20, `the raster ground is lit (${r.toFixed(1)})`);
  assert.ok(Math.abs(p - r) / r < 0.15, `ground: path traced ${p.toFixed(1)} vs raster ${r.toFixed(1)}`);
});
