import { test } from 'node:test';
import assert from 'node:assert/strict';
import { mat4d, vec3d } from 'wgpu-matrix';
import { createSceneTimeline } from '../../src/animation/timeline/scene-timeline.ts';
import { evaluateLayeredPose } from '../../src/animation/pose/evaluate-layers.ts';
import { evaluateClipPose } from '../../src/animation/pose/evaluate-clip.ts';
import { bakePose } from '../../src/animation/skinning/bake-pose.ts';
import { normalizeWavefrontMesh } from '../../src/scene/mesh.ts';
import { createFigureSetup } from './fixtures/figure-library.ts';
import { assertClose, assertNear } from './helpers.ts';

const setup = createFigureSetup();
const route = [{ position: [0, 0, 0], arriveMs: 0 }, { position: [0, 0, 10], arriveMs: 10000 }];
const beats = [
  { id: 'stroll', order: 1, clipId: 'walk', durationMs: 1000, blend: { outMs: 200 }, movementRequirement: { kind: 'travel' } },
  { id: 'pause', order: 2, clipId: 'idle', durationMs: 2000, blend: { inMs: 300 }, movementRequirement: { kind: 'stationary' } },
  { id: 'opening', order: 0, clipId: 'idle', durationMs: 500, blend: { inMs: 400 } },
];

test('beats play in order; cross-fades span [T - outMs, T + inMs] with linear weights', () => {
  const timeline = createSceneTimeline(setup.library, { beats, route });
  assert.deepEqual(timeline.beats.map((b) => [b.id, b.startMs, b.endMs]), [['opening', 0, 500], ['stroll', 500, 1500], ['pause', 1500, 3500]]);
  assert.equal(timeline.durationMs, 3500);
  const early = timeline.sample(100);
  assert.equal(early.activeBeatId, 'opening');
  assert.equal(early.layers.length, 1, "the first beat's inMs has nothing to blend from");
  assert.equal(early.blendProgress, 1);
  // Boundary stroll -> pause at T = 1500: window [1300, 1800].
  const before = timeline.sample(1400);
  assert.equal(before.activeBeatId, 'stroll');
  assert.deepEqual(before.layers.map((l) => l.clip.name), ['Walk', 'Idle']);
  assertClose(before.layers.map((l) => l.weight), [0.8, 0.2], 1e-12, 'weights at 1400');
  assertNear(before.blendProgress, 0.2, 1e-12, 'progress');
  assertNear(before.layers[1].clipTimeMs, 100, 1e-9, 'the incoming clip starts when its fade starts');
  const after = timeline.sample(1600);
  assert.equal(after.activeBeatId, 'pause');
  assert.equal(after.activeClipId, 'idle');
  assertClose(after.layers.map((l) => l.weight), [0.4, 0.6], 1e-12, 'weights at 1600');
  assertNear(after.clipTimeMs, 300, 1e-9, 'active clip time');
  const settled = timeline.sample(2000);
  assert.equal(settled.layers.length, 1);
  assert.equal(settled.blendProgress, 1);
  // The stroll's walk clip loops over its window: 1000 ms after its start it is back at time 0.
  assertNear(timeline.sample(1499).layers[0].clipTimeMs, 999, 1e-9, 'walk near the end of its loop');
  // After the last beat its clip keeps looping: (5000 - 1300) mod 2000.
  assertNear(timeline.sample(5000).clipTimeMs, 1700, 1e-9, 'idle loops after the end');
  assert.equal(timeline.sample(5000).activeBeatId, 'pause');
});

test('blend weights rise monotonically and sum to 1 through a cross-fade', () => {
  const timeline = createSceneTimeline(setup.library, { beats, route });
  let last = -1;
  for (let t = 1300; t <= 1800; t += 25) {
    const s = timeline.sample(t);
    const incoming = s.layers.length === 2 ? s.layers[1].weight : 1;
    assert.ok(incoming >= last, `weight at ${t}`);
    last = incoming;
    assertNear(s.layers.reduce((sum, l) => sum + l.weight, 0), 1, 1e-12, `sum at ${t}`);
  }
});

test('in-place layers keep the root over its start position horizontally and keep its vertical motion', () => {
  const { model } = setup;
  const walk = setup.library.clips.get('walk')!;
  const hips = model.nodes.findIndex((n) => n.name === 'Hips');
  const authored = evaluateClipPose(model, walk.clip, 0.25);
  assertClose(authored.translations.subarray(3 * hips, 3 * hips + 3), [0, 2.05, 0.5], 1e-6, 'authored');
  const inPlace = evaluateLayeredPose(model, [{ clip: walk.clip, clipTimeMs: 250, weight: 1, rootMotion: 'in-place', root: walk.root }]);
  assertClose(inPlace.translations.subarray(3 * hips, 3 * hips + 3), [0, 2.05, 0], 1e-6, 'in place');
});

test('bakePose of a timeline places the skinned body with the character transform, and the rigid badge on the head', () => {
  const { model, document } = setup;
  const timeline = createSceneTimeline(setup.library, { beats, route });
  const t = 1000; // mid-stroll: walking, in place, the route moves the character
  const baked = bakePose(model, timeline, t);
  assert.equal(baked.meshes.length, 2);
  // Structural check with the scene's mesh validator (material references are resolved by the scene, not here).
  baked.meshes.forEach((mesh, i) => normalizeWavefrontMesh({ ...mesh, material: undefined }, i));
  const character = timeline.characterAt(t);
  assertNear(character.position[2], 0.5, 1e-9, 'half a metre along the route after 500 ms of walking');
  const body = baked.meshes.findIndex((m) => String(m.id).includes(`node${model.nodes.findIndex((n) => n.name === 'Body')}.`));
  assertClose(baked.instances[body].transform!, character.rootTransform, 0, 'skinned: instance = character placement');
  // Badge: rigid child of Head; its world vertex = root x world(Head) x local(Badge) x p, from gltf-transform's graph.
  const badgeIndex = 1 - body;
  const nodes = document.getRoot().listNodes();
  const pose = baked.pose;
  nodes.forEach((node, i) => {
    node.setTranslation([...pose.translations.subarray(3 * i, 3 * i + 3)] as [number, number, number]);
    node.setRotation([...pose.rotations.subarray(4 * i, 4 * i + 4)] as [number, number, number, number]);
    node.setScale([...pose.scales.subarray(3 * i, 3 * i + 3)] as [number, number, number]);
  });
  const badgeNode = nodes.find((n) => n.getName() === 'Badge')!;
  const expected = mat4d.multiply(character.rootTransform, Float64Array.from(badgeNode.getWorldMatrix()));
  assertClose(baked.instances[badgeIndex].transform!, expected, 1e-12, 'badge instance transform');
  const p = vec3d.transformMat4([0, 0.08, 0], expected);
  const q = vec3d.transformMat4(Array.from(baked.meshes[badgeIndex].positions).slice(6, 9), baked.instances[badgeIndex].transform!);
  assertClose(q, p, 1e-6, 'badge tip in world space (float32 vertex streams)');
  // Materials refer to glTF material indices.
  assert.equal(typeof baked.meshes[body].material, 'number');
  assert.equal(model.materials[baked.meshes[body].material as number].name, 'Skin');
});

test('bakePose of a single clip: the still at time t equals skinning the clip pose at t', () => {
  const { model } = setup;
  const idle = setup.library.clips.get('idle')!;
  const a = bakePose(model, { clip: idle.clip }, 2500); // loops: 500 ms into the idle
  const b = bakePose(model, { clip: idle.clip, loop: false }, 500);
  const bodyMesh = (baked: typeof a): ArrayLike<number> => baked.meshes.find((m) => String(m.id).includes('mesh') && m.uvs !== undefined)!.positions;
  assertClose(bodyMesh(a), bodyMesh(b), 0, 'looped and unlooped at the same clip time');
  const body = model.nodes.findIndex((n) => n.name === 'Body');
  assertClose(a.pose.weights[body], [0.5], 1e-7, 'morph weight half way up at 0.5 s');
});
