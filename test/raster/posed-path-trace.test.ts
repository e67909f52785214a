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
