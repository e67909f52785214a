// A real browser: Debian's Chromium (SwiftShader WebGPU) draws the animated scene on a canvas. The
// GLB is generated here and handed to the page as bytes; the presented canvas must show the
// textured character where the CPU-posed silhouette (the animation core in Node, same options)
// projects, and the snapshot must describe the WebGPU PBR path.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { WebIO } from '@gltf-transform/core';
import { decode } from 'fast-png';
import { createAnimatedSceneCore } from '../../src/animation/animated-scene-core.ts';
import type * as Pkg from '../../src/index.ts';
import { ADVENTURE_BEATS, ADVENTURE_CAMERA, ADVENTURE_CLIPS, ADVENTURE_ROUTE, adventureFigure, characterClass } from '../animation/fixtures/adventure-scene.ts';
import { cpuSilhouette, maskOverlap } from '../raster/silhouette.ts';
import { chromiumSkip, openPackagePage } from './browser-session.ts';

const W = 96;
const H = 72;
const T = 1250;

test('Chromium: the animated scene renderer draws the skinned character on a WebGPU canvas', { skip: chromiumSkip }, async (t) => {
  const { tab, pageErrors, close } = await openPackagePage({
    style: `html, body { margin: 0; } canvas { display: block; width: ${W}px; height: ${H}px; }`,
    body: `<canvas id="scene" width="${W}" height="${H}"></canvas>`,
    viewport: { width: 160, height: 120 },
  });
  t.after(close);
  const glb = await new WebIO().writeBinary(adventureFigure().document);
  const snapshot = await tab.evaluate(
    async ({ bytes, W, H, T, clips, beats, route, camera }) => {
      const { createAnimatedSceneRenderer } = (window as unknown as { pkg: typeof Pkg }).pkg;
      const renderer = await createAnimatedSceneRenderer({ canvas: '#scene', width: W, height: H, modelAsset: new Uint8Array(bytes), clipAssets: clips, beats, route, camera, shadow: { mapSize: 512 } });
      const s = await renderer.renderOnce(T);
      return JSON.parse(JSON.stringify(s)) as Pkg.AnimatedSceneSnapshot;
    },
    { bytes: Array.from(glb), W, H, T, clips: ADVENTURE_CLIPS, beats: ADVENTURE_BEATS, route: ADVENTURE_ROUTE, camera: ADVENTURE_CAMERA },
  );
  assert.deepEqual(pageErrors, []);
  assert.equal(snapshot.renderMode, 'webgpu-pbr');
  assert.equal(snapshot.activeBeatId, 'stroll');
  assert.equal(snapshot.characterVisible, true);
  const png = decode(await tab.locator('#scene').screenshot());
  assert.deepEqual([png.width, png.height], [W, H]);
  const channels = png.data.length / (W * H);
  const rgba = Uint8Array.from({ length: 4 * W * H }, (_, i) => png.data[Math.floor(i / 4) * channels + (i % 4)] ?? 255);
  const drawn = Uint8Array.from({ length: W * H }, (_, i) => (characterClass(rgba, i) > 0 ? 1 : 0));
  // The same scene posed on the CPU in Node.
  const core = createAnimatedSceneCore({ modelAsset: adventureFigure().document, clipAssets: ADVENTURE_CLIPS, beats: ADVENTURE_BEATS, route: ADVENTURE_ROUTE, camera: ADVENTURE_CAMERA });
  const frame = core.frame(T);
  const baked = core.bakePose(T);
  const cam = frame.camera.transform;
  const expected = cpuSilhouette({ meshes: baked.meshes, instances: baked.instances, camera: { position: cam.position, target: cam.target, up: cam.up, fovYDegrees: cam.fovYDegrees } }, (i) => baked.meshes[i]!.positions.length > 9, W, H);
  const overlap = maskOverlap(drawn, expected);
  assert.ok(overlap.b > 60, `CPU silhouette ${overlap.b} px`);
  assert.ok(overlap.iou > 0.85, `canvas vs CPU silhouette IoU ${overlap.iou.toFixed(3)} (${overlap.a} vs ${overlap.b} px)`);
  let upper = 0, lower = 0;
  for (let i = 0; i < W * H; i++) {
    const c = characterClass(rgba, i);
    if (c === 1) upper++;
    if (c === 2) lower++;
  }
  assert.ok(upper > 10 && lower > 10, `texture colours on the canvas: ${upper} blue, ${lower} orange`);
});
