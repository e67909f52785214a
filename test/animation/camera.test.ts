import { test } from 'node:test';
import assert from 'node:assert/strict';
import { vec3d } from 'wgpu-matrix';
import { createCameraController } from '../../src/animation/camera/camera-controller.ts';
import { createCharacterCameraSubject } from '../../src/animation/camera/camera-subject.ts';
import { cubicBezierEasing } from '../../src/animation/camera/cubic-bezier.ts';
import { createLaggedFollow } from '../../src/animation/camera/lagged-follow.ts';
import { evaluateLayeredPose } from '../../src/animation/pose/evaluate-layers.ts';
import { bakePose } from '../../src/animation/skinning/bake-pose.ts';
import { createSceneTimeline } from '../../src/animation/timeline/scene-timeline.ts';
import { createFigureSetup } from './fixtures/figure-library.ts';
import { assertClose, assertNear, expectRendererError } from './helpers.ts';

const setup = createFigureSetup();
const route = [{ position: [0, 0, 0], arriveMs: 0 }, { position: [0, 0, 6], arriveMs: 6000 }, { position: [4, 0, 6], arriveMs: 10000 }];
const beats = [
  { id: 'walk', order: 0, clipId: 'walk', durationMs: 6000, blend: { outMs: 300 }, movementRequirement: { kind: 'travel' } },
  { id: 'idle', order: 1, clipId: 'idle', durationMs: 2000, blend: { inMs: 300 }, movementRequirement: { kind: 'stationary' } },
];
const timeline = createSceneTimeline(setup.library, { beats, route });
const subject = createCharacterCameraSubject(setup.model, timeline);

test('cubic-bezier easing follows the CSS parametric curve', () => {
  for (const curve of [[0.25, 0.1, 0.25, 1], [0.42, 0, 1, 1], [0, 0, 0.58, 1], [0.7, -0.4, 0.2, 1.5]] as const) {
    const ease = cubicBezierEasing(curve);
    for (let s = 0.05; s < 1; s += 0.1) {
      // Direct evaluation of the Bezier polynomials at parameter s.
      const x = 3 * (1 - s) ** 2 * s * curve[0] + 3 * (1 - s) * s * s * curve[2] + s ** 3;
      const y = 3 * (1 - s) ** 2 * s * curve[1] + 3 * (1 - s) * s * s * curve[3] + s ** 3;
      assertNear(ease(x), y, 1e-9, `curve ${curve.join(',')} at s = ${s.toFixed(2)}`);
    }
    assert.equal(ease(0), 0);
    assert.equal(ease(1), 1);
  }
  const linear = cubicBezierEasing([0, 0, 1, 1]);
  for (const x of [0.1, 0.5, 0.93]) assertNear(linear(x), x, 1e-9, 'linear');
});

test('follow lag: exact exponential smoothing of a constant-velocity target, v x lag behind in steady state', () => {
  const lagMs = 300;
  const v = [0.002, 0, -0.001]; // metres per ms
  const desired = (t: number): [number, number, number] => [1 + v[0] * t, 2, 3 + v[2] * t];
  const follow = createLaggedFollow(lagMs);
  for (const t of [10, 123.4, 1000, 2500]) {
    const x = follow.valueAt(t, desired);
    // dx/dt = (d - x) / tau with x(0) = d(0): x(t) = d(t) - v tau (1 - e^(-t / tau)).
    const k = 1 - Math.exp(-t / lagMs);
    assertClose(x, [desired(t)[0] - v[0] * lagMs * k, 2, desired(t)[2] - v[2] * lagMs * k], 1e-12, `t = ${t}`);
  }
  // Time constant: a unit step at 500 ms is 1 - 1/e done one lag later (tick-sampled step: within 2%).
  const step = createLaggedFollow(lagMs);
  const stepTarget = (t: number): [number, number, number] => [t >= 500 ? 1 : 0, 0, 0];
  assertNear(step.valueAt(500 + lagMs, stepTarget)[0], 1 - Math.exp(-1), 0.02, 'one time constant');
  assert.deepEqual(createLaggedFollow(0).valueAt(777, desired), desired(777), 'no lag: the target itself');
});

test('follow lag is frame-rate independent: any frame sequence gives the same camera at the same time', () => {
  const circle = (t: number): [number, number, number] => [Math.cos(t / 700), 0.3 * Math.sin(t / 300), Math.sin(t / 700)];
  const end = 2345.6;
  const run = (frames: number[]): [number, number, number] => {
    const follow = createLaggedFollow(250);
    let last: [number, number, number] = [0, 0, 0];
    for (const t of frames) last = follow.valueAt(t, circle);
    return last;
  };
  const every = (dt: number): number[] => {
    const frames: number[] = [];
    for (let t = 0; t < end; t += dt) frames.push(t);
    frames.push(end);
    return frames;
  };
  let seed = 1;
  const jitter: number[] = [];
  for (let t = 0; t < end; t += 5 + ((seed = (seed * 16807) % 2147483647) % 40)) jitter.push(t);
  jitter.push(end);
  const reference = run([end]);
  for (const frames of [every(1000 / 60), every(1000 / 144), every(1000 / 24), jitter]) assertClose(run(frames), reference, 1e-12, 'same value');
  // Seeking backwards replays from the start and lands on the same value too.
  const follow = createLaggedFollow(250);
  follow.valueAt(5000, circle);
  assertClose(follow.valueAt(end, circle), reference, 1e-12, 'after a backwards seek');
});

test('third-person: distance clamped to [min, max] through zoom and over a walk; look-ahead aims ahead of the pivot', () => {
  const camera = createCameraController({ offset: [0, 3, -20], lagMs: 200, lookAheadMs: 500, constraints: { minDistance: 2, maxDistance: 8 } }, { hasHeadAnchor: true });
  for (let t = 0; t <= 9000; t += 450) {
    const out = camera.evaluate(t, subject);
    assert.ok(out.targetDistance >= 2 - 1e-12 && out.targetDistance <= 8 + 1e-12, `distance ${out.targetDistance} at ${t}`);
  }
  assertNear(camera.evaluate(1000, subject).targetDistance, 8, 1e-12, 'offset of length ~20.2 clamped to 8');
  camera.applyControl({ zoom: 100 });
  assertNear(camera.evaluate(1000, subject).targetDistance, 2, 1e-12, 'zoomed in to the minimum');
  camera.applyControl({ zoom: -3 });
  assertNear(camera.evaluate(1000, subject).targetDistance, 5, 1e-12, 'zoomed out 3 m');
  camera.applyControl({ orbit: [0, 10] });
  const high = camera.evaluate(1000, subject).transform;
  const pivotToCamera = high.position[1] - (high.target[1]); // target is pivot + velocity * lookAhead, velocity horizontal
  assertNear(Math.asin(pivotToCamera / 5), (70 * Math.PI) / 180, 1e-9, 'pitch clamped at the default 70 degrees');
  // Look-ahead: walking +Z at 1 m/s, the aim is 0.5 m ahead of the pivot.
  const steady = createCameraController({ lagMs: 0, lookAheadMs: 500 }, { hasHeadAnchor: true }).evaluate(2000, subject);
  const focus = subject.focusAt(2000);
  assertClose(steady.transform.target, [focus[0], focus[1], focus[2] + 0.5], 1e-9, 'look-ahead target');
});

test('first-person: the camera sits on the head anchor of the animated pose; look is clamped to the head limits', () => {
  const camera = createCameraController({ viewMode: 'first-person', constraints: { headYawLimitDegrees: 60, headPitchLimitDegrees: 30 } }, { hasHeadAnchor: true });
  const { document, model } = setup;
  const nodes = document.getRoot().listNodes();
  for (const t of [0, 1250, 4100, 6150, 7000]) {
    const out = camera.evaluate(t, subject);
    // Independent head position: gltf-transform's scene graph with the posed TRS, then the character placement.
    const sample = timeline.sample(t);
    const pose = evaluateLayeredPose(model, sample.layers);
    nodes.forEach((node, i) => {
      node.setTranslation([...pose.translations.subarray(3 * i, 3 * i + 3)] as [number, number, number]);
      node.setRotation([...pose.rotations.subarray(4 * i, 4 * i + 4)] as [number, number, number, number]);
      node.setScale([...pose.scales.subarray(3 * i, 3 * i + 3)] as [number, number, number]);
    });
    const headWorld = nodes.find((n) => n.getName() === 'Head')!.getWorldMatrix();
    const expected = vec3d.transformMat4([headWorld[12], headWorld[13], headWorld[14]], sample.rootTransform);
    assertClose(out.transform.position, expected, 1e-9, `head anchor at ${t}`);
    assertNear(out.targetDistance, 0, 0, 'first person has no follow distance');
  }
  camera.applyControl({ look: [5, -5] });
  const out = camera.evaluate(1000, subject);
  assertNear(out.headLook.yaw, Math.PI / 3, 1e-12, 'yaw clamped to 60 degrees');
  assertNear(out.headLook.pitch, -Math.PI / 6, 1e-12, 'pitch clamped to -30 degrees');
  const heading = timeline.characterAt(1000).yaw;
  assertClose(out.transform.forward, [Math.sin(heading + Math.PI / 3) * Math.cos(Math.PI / 6), -0.5, Math.cos(heading + Math.PI / 3) * Math.cos(Math.PI / 6)], 1e-12, 'view direction');
  assert.ok(out.headLook.active);
});

test('head-look is reported as intent and never written into clip data or the pose', () => {
  const walk = setup.library.clips.get('walk')!.clip;
  const outputsBefore = walk.channels.map((c) => Float64Array.from(c.sampler.output));
  const before = bakePose(setup.model, timeline, 2500).meshes.map((m) => Float32Array.from(m.positions));
  const camera = createCameraController({}, { hasHeadAnchor: true });
  assert.equal(camera.evaluate(2500, subject).headLook.active, false);
  camera.applyControl({ look: [0.4, 0.2] });
  const out = camera.evaluate(2500, subject);
  assert.deepEqual([out.headLook.active, out.headLook.yaw, out.headLook.pitch], [true, 0.4, 0.2]);
  const heading = timeline.characterAt(2500).yaw;
  assertClose(out.headLook.direction, [Math.sin(heading + 0.4) * Math.cos(0.2), Math.sin(0.2), Math.cos(heading + 0.4) * Math.cos(0.2)], 1e-12, 'direction');
  walk.channels.forEach((c, i) => assert.deepEqual(c.sampler.output, outputsBefore[i], `channel ${i} unchanged`));
  bakePose(setup.model, timeline, 2500).meshes.forEach((m, i) => assert.deepEqual(Float32Array.from(m.positions), before[i], `mesh ${i} pose unchanged`));
});

test('editor orbits, pans and zooms about its pivot; spectator flies', () => {
  const camera = createCameraController({ viewMode: 'editor', position: [0, 2, 5], target: [0, 1, 0] }, { hasHeadAnchor: true });
  const start = camera.evaluate(0, subject);
  assertClose(start.transform.position, [0, 2, 5], 1e-12, 'explicit pose');
  assertNear(start.targetDistance, Math.hypot(1, 5), 1e-12, 'orbit distance');
  camera.applyControl({ pan: [1, 0] });
  const panned = camera.evaluate(0, subject);
  const right = [-start.transform.forward[2], 0, start.transform.forward[0]];
  const rl = Math.hypot(...right);
  assertClose(panned.transform.target, [right[0] / rl, 1, right[2] / rl], 1e-12, 'pivot moved 1 m right');
  assertNear(panned.targetDistance, start.targetDistance, 1e-12, 'pan keeps the distance');
  camera.applyControl({ zoom: 2 });
  assertNear(camera.evaluate(0, subject).targetDistance, Math.hypot(1, 5) - 2, 1e-12, 'zoom');
  camera.applyControl({ orbit: [Math.PI, 0] });
  const orbited = camera.evaluate(0, subject);
  assertNear(vec3d.distance(orbited.transform.position, orbited.transform.target), Math.hypot(1, 5) - 2, 1e-12, 'orbit keeps the distance');
  const fly = createCameraController({ viewMode: 'spectator', position: [0, 2, 0], target: [0, 2, 1] }, { hasHeadAnchor: true });
  fly.applyControl({ move: [2, 0, 1] });
  assertClose(fly.evaluate(0, subject).transform.position, [0, 3, 2], 1e-12, 'flew 2 m forward and 1 m up');
  fly.applyControl({ look: [Math.PI / 2, 0] });
  assertClose(fly.evaluate(0, subject).transform.forward, [1, 0, 0], 1e-12, 'turned to +X');
});

test('view-mode transitions ease from the last transform with the cubic-bezier curve', () => {
  const curve = [0.42, 0, 0.58, 1] as const;
  const camera = createCameraController({ transitionMs: 400, cubicBezier: curve, lagMs: 0 }, { hasHeadAnchor: true });
  const from = camera.evaluate(1000, subject).transform;
  camera.setViewMode('first-person');
  const reference = createCameraController({ viewMode: 'first-person', lagMs: 0 }, { hasHeadAnchor: true });
  const to = reference.evaluate(1100, subject).transform;
  const out = camera.evaluate(1100, subject);
  const e = cubicBezierEasing(curve)(0.25);
  assertNear(out.transitionProgress, e, 1e-12, 'eased progress');
  assertClose(out.transform.position, [0, 1, 2].map((i) => from.position[i] + (to.position[i] - from.position[i]) * e), 1e-12, 'blended position');
  const done = camera.evaluate(1400, subject);
  assert.equal(done.transitionProgress, 1);
  assertClose(done.transform.position, reference.evaluate(1400, subject).transform.position, 0, 'transition over');
});

test('camera options and controls are validated with typed errors', () => {
  const ctx = { hasHeadAnchor: true };
  expectRendererError(() => createCameraController({ viewMode: 'drone' }, ctx), 'INVALID_OPTION', 'camera.viewMode');
  expectRendererError(() => createCameraController({ lagMs: -1 }, ctx), 'INVALID_OPTION', 'camera.lagMs');
  expectRendererError(() => createCameraController({ offset: [0, NaN, 1] }, ctx), 'INVALID_OPTION', 'camera.offset[1]');
  expectRendererError(() => createCameraController({ cubicBezier: [1.5, 0, 0.5, 1] }, ctx), 'INVALID_OPTION', 'camera.cubicBezier[0]');
  expectRendererError(() => createCameraController({ constraints: { minDistance: 5, maxDistance: 2 } }, ctx), 'INVALID_OPTION', 'camera.constraints.maxDistance');
  expectRendererError(() => createCameraController({ viewMode: 'first-person' }, { hasHeadAnchor: false }), 'INVALID_MODEL', 'camera.headJoint');
  const camera = createCameraController({}, ctx);
  expectRendererError(() => camera.applyControl({ orbit: [0, Infinity] }), 'INVALID_OPTION', 'control.orbit[1]');
  expectRendererError(() => camera.setViewMode('orbit' as never), 'INVALID_OPTION', 'camera.viewMode');
  expectRendererError(() => createCharacterCameraSubject(setup.model, timeline, { headJoint: 'Skull' }), 'INVALID_OPTION', 'camera.headJoint');
});
