// createAnimatedSceneRenderer offscreen on Dawn: the textured, GPU-skinned character appears where
// the CPU-posed silhouette (bakePose, projected with the snapshot's camera) says, with its texture
// colours; the pose changes between frames as the clip says; snapshot fields and camera-rig
// constraints match values computed independently.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createAnimatedSceneRenderer, type AnimatedSceneRenderer } from '../../src/raster/index.ts';
import type { WavefrontSceneDescription } from '../../src/scene/types.ts';
import { ADVENTURE_BEATS, ADVENTURE_CAMERA, ADVENTURE_CLIPS, ADVENTURE_PROPS, ADVENTURE_ROUTE, adventureFigure, characterClass } from '../animation/fixtures/adventure-scene.ts';
import { testDevice } from '../helpers/gpu.ts';
import { cpuSilhouette, maskOverlap } from './silhouette.ts';

const W = 96;
const H = 72;

async function adventure(extra: Record<string, unknown> = {}): Promise<AnimatedSceneRenderer> {
  return createAnimatedSceneRenderer({
    device: await testDevice(),
    width: W,
    height: H,
    modelAsset: adventureFigure().document,
    clipAssets: ADVENTURE_CLIPS,
    beats: ADVENTURE_BEATS,
    route: ADVENTURE_ROUTE,
    props: ADVENTURE_PROPS,
    camera: ADVENTURE_CAMERA,
    shadow: { mapSize: 512 },
    ...extra,
  });
}

const isCharacterMesh = (scene: WavefrontSceneDescription) => (i: number): boolean => String(scene.meshes![i]!.id ?? '').startsWith('node') && scene.meshes![i]!.positions.length > 9;

function characterMask(data: ArrayLike<number>): Uint8Array {
  return Uint8Array.from({ length: W * H }, (_, i) => (characterClass(data, i) > 0 ? 1 : 0));
}

test('the skinned character is drawn where its CPU-posed silhouette projects, with its texture colours, and its pose follows the clip', async (t) => {
  const renderer = await adventure();
  t.after(() => renderer.destroy());
  const masks: Uint8Array[] = [];
  for (const tMs of [1250, 1750]) {
    const snapshot = await renderer.renderOnce(tMs);
    const pixels = await renderer.readPixels();
    const scene = renderer.posedScene(tMs);
    const expected = cpuSilhouette(scene, isCharacterMesh(scene), W, H);
    const drawn = characterMask(pixels.data);
    const overlap = maskOverlap(drawn, expected);
    assert.ok(overlap.b > 60, `the character covers ${overlap.b} pixels`);
    assert.ok(overlap.iou > 0.85, `t = ${tMs}: drawn vs CPU silhouette IoU ${overlap.iou.toFixed(3)} (${overlap.a} vs ${overlap.b} px)`);
    // Both texture rows are present: blue upper body above orange legs.
    let upper = 0, lower = 0, upperY = 0, lowerY = 0;
    for (let i = 0; i < W * H; i++) {
      const c = characterClass(pixels.data, i);
      if (c === 1) { upper++; upperY += Math.floor(i / W); }
      if (c === 2) { lower++; lowerY += Math.floor(i / W); }
    }
    assert.ok(upper > 20 && lower > 10, `texture colours: ${upper} blue and ${lower} orange pixels`);
    assert.ok(upperY / upper < lowerY / lower, 'the upper-body colour is above the leg colour');
    // The snapshot's projected bounds contain the drawn character.
    const [x0, y0, x1, y1] = snapshot.characterScreenBounds!;
    for (let i = 0; i < W * H; i++) {
      if (!drawn[i]) continue;
      const x = i % W, y = Math.floor(i / W);
      assert.ok(x >= x0 - 1 && x <= x1 + 1 && y >= y0 - 1 && y <= y1 + 1, `character pixel (${x}, ${y}) outside the snapshot bounds ${snapshot.characterScreenBounds}`);
    }
    assert.equal(snapshot.characterVisible, true);
    masks.push(drawn);
  }
  // Walk clip times 250 and 750 ms swing the legs to opposite sides: the silhouettes differ.
  const change = maskOverlap(masks[0]!, masks[1]!);
  assert.ok(change.iou < 0.9, `the pose changed between frames (IoU of the two frames ${change.iou.toFixed(3)})`);
});

test('snapshot fields equal the timeline, movement and camera-rig values', async (t) => {
  const renderer = await adventure();
  t.after(() => renderer.destroy());
  const idle = await renderer.renderOnce(500);
  assert.equal(idle.activeBeatId, 'wait');
  assert.equal(idle.activeClipId, 'idle');
  assert.equal(idle.rootMotionPolicy, 'in-place');
  assert.deepEqual(idle.characterPosition, [0, 0, 0]);
  assert.equal(idle.characterGroundY, 0);
  assert.equal(idle.fallbackProxyActive, false);
  assert.equal(idle.renderMode, 'webgpu-pbr');
  assert.equal(idle.modelRenderable, true);
  assert.equal(idle.activeClipRenderable, true);
  assert.equal(idle.skinnedVertexCount, 48);
  assert.equal(idle.skinnedJointCount, 5);
  assert.equal(idle.frame, 1);
  assert.deepEqual(idle.propGroundAnchors, [{ kind: 'rock', position: [1.6, 0, 2.5], groundY: 0 }]);
  assert.equal(idle.movementValidation.valid, true, JSON.stringify(idle.movementValidation.diagnostics));
  // Third person without lag: camera = focus + offset (its length 3.92 m lies inside [1.5, 12]).
  const focus = [0, idle.cameraTransform.target[1], 0];
  const offsetLength = Math.hypot(...ADVENTURE_CAMERA.offset);
  for (let k = 0; k < 3; k++) assert.ok(Math.abs(idle.cameraPosition[k]! - (focus[k]! + ADVENTURE_CAMERA.offset[k]!)) < 1e-9, `camera ${k}`);
  assert.ok(Math.abs(idle.targetDistance - offsetLength) < 1e-9);
  // Walking: 1 m per 1 s loop of authored root motion from t = 1000 ms.
  const walking = await renderer.renderOnce(2500);
  assert.equal(walking.activeBeatId, 'stroll');
  assert.equal(walking.rootMotionPolicy, 'authored-travel');
  assert.ok(Math.abs(walking.characterPosition[2] - 1.5) < 1e-9, `z ${walking.characterPosition[2]}`);
  assert.ok(Math.abs(walking.clipTimeMs - 500 - 100) < 1e-6 || Math.abs(walking.clipTimeMs - 600) < 1e-6, `clip time ${walking.clipTimeMs}`);
  // Constraints: zooming in past minDistance clamps third-person distance to 1.5 m.
  renderer.applyCameraControl({ zoom: 10 });
  const zoomed = await renderer.renderOnce(2500);
  assert.ok(Math.abs(zoomed.targetDistance - 1.5) < 1e-9, `clamped distance ${zoomed.targetDistance}`);
  // First person from the head anchor: the camera sits on the head joint.
  renderer.setCameraViewMode('first-person');
  const fp = await renderer.renderOnce(2500);
  assert.equal(fp.cameraViewMode, 'first-person');
  assert.equal(fp.targetDistance, 0);
  assert.ok(fp.cameraPosition[1] > 1.5 && fp.cameraPosition[1] < 2.0, `head height ${fp.cameraPosition[1]}`);
  // Head look is reported as intent and never changes the clip pose.
  renderer.setCameraViewMode('third-person');
  renderer.applyCameraControl({ look: [0.3, 0.1] });
  const looking = await renderer.renderOnce(2500);
  assert.equal(looking.headLook.active, true);
  assert.ok(Math.abs(looking.headLook.yaw - 0.3) < 1e-12);
  assert.equal(looking.clipTimeMs, walking.clipTimeMs);
});

test('start() runs frames on the injected requestAnimationFrame with scene time from the first timestamp; stop() cancels', async (t) => {
  const queue = new Map<number, (ts: number) => void>();
  let next = 1;
  const frames: { frame: number; timeMs: number; clipTimeMs: number }[] = [];
  let done: () => void = () => undefined;
  let loopError: unknown = null;
  const renderer = await adventure({
    msaa: 1,
    requestAnimationFrame: (cb: (ts: number) => void) => {
      queue.set(next, cb);
      return next++;
    },
    cancelAnimationFrame: (handle: unknown) => queue.delete(handle as number),
    onError: (error: unknown) => {
      loopError = error;
      done();
    },
    onFrame: (s: { frame: number; timeMs: number; clipTimeMs: number }) => {
      frames.push({ frame: s.frame, timeMs: s.timeMs, clipTimeMs: s.clipTimeMs });
      done();
    },
  });
  t.after(() => renderer.destroy());
  renderer.start();
  const fire = async (timestamp: number): Promise<void> => {
    const rendered = new Promise<void>((resolve) => (done = resolve));
    const [handle, cb] = [...queue.entries()][0]!;
    queue.delete(handle);
    cb(timestamp);
    await rendered;
  };
  await fire(10_000);
  await fire(10_400);
  assert.equal(loopError, null);
  assert.deepEqual(frames.map((f) => f.timeMs), [0, 400]);
  assert.deepEqual(frames.map((f) => f.frame), [1, 2]);
  // Idle clip time follows scene time (the idle beat plays from 0 ms).
  assert.equal(frames[1]!.clipTimeMs, 400);
  assert.equal(renderer.getSnapshot()!.timeMs, 400);
  renderer.stop();
  assert.equal(queue.size, 0, 'stop cancels the pending frame');
});
