import { test } from 'node:test';
import assert from 'node:assert/strict';
import { mat4d } from 'wgpu-matrix';
import { readAnimatedModel } from '../../src/animation/model/read-model.ts';
import { evaluateClipPose, loopClipTimeMs } from '../../src/animation/pose/evaluate-clip.ts';
import { blendPoses } from '../../src/animation/pose/blend-poses.ts';
import { createRestPose } from '../../src/animation/pose/pose.ts';
import { computeJointMatrices, computeWorldMatrices } from '../../src/animation/pose/world-matrices.ts';
import { axisAngleQuaternion, createRiggedFigure } from './fixtures/rigged-figure.ts';
import { assertClose, assertSameRotation } from './helpers.ts';

test('world matrices of a sampled walk pose equal gltf-transform world matrices of the same TRS', () => {
  const { document } = createRiggedFigure();
  const model = readAnimatedModel(document);
  const nodes = document.getRoot().listNodes();
  for (const t of [0, 0.2, 0.5, 0.77]) {
    const pose = evaluateClipPose(model, model.clips[0], t);
    const world = computeWorldMatrices(model, pose);
    nodes.forEach((node, i) => {
      node.setTranslation([...pose.translations.subarray(3 * i, 3 * i + 3)] as [number, number, number]);
      node.setRotation([...pose.rotations.subarray(4 * i, 4 * i + 4)] as [number, number, number, number]);
      node.setScale([...pose.scales.subarray(3 * i, 3 * i + 3)] as [number, number, number]);
    });
    nodes.forEach((node, i) => assertClose(world.subarray(16 * i, 16 * i + 16), node.getWorldMatrix(), 1e-12, `${node.getName()} at ${t}`));
  }
});

test('a clip pose writes sampled values over the rest pose and leaves other nodes at rest', () => {
  const model = readAnimatedModel(createRiggedFigure().document);
  const hips = model.nodes.findIndex((n) => n.name === 'Hips');
  const leftLeg = model.nodes.findIndex((n) => n.name === 'LeftLeg');
  const head = model.nodes.findIndex((n) => n.name === 'Head');
  const pose = evaluateClipPose(model, model.clips[0], 0.25);
  assertClose(pose.translations.subarray(3 * hips, 3 * hips + 3), [0, 2.05, 0.5], 1e-6, 'hips halfway to the second key');
  assertSameRotation(pose.rotations.subarray(4 * leftLeg, 4 * leftLeg + 4), [0, 0, 0, 1], 1e-7, 'leg halfway between +30 and -30 degrees');
  assertClose(pose.rotations.subarray(4 * head, 4 * head + 4), model.nodes[head].rotation, 0, 'head untouched by Walk');
  const body = model.nodes.findIndex((n) => n.name === 'Body');
  const idle = evaluateClipPose(model, model.clips[1], 0.5);
  assertClose(idle.weights[body], [0.5], 1e-7, 'morph weight halfway');
});

test('loopClipTimeMs wraps into [0, duration)', () => {
  assert.equal(loopClipTimeMs(2500, 1), 500);
  assert.equal(loopClipTimeMs(-250, 1), 750);
  assert.equal(loopClipTimeMs(1000, 1), 0);
  assert.equal(loopClipTimeMs(123, 0), 0);
});

test('blending: weights 1/0 reproduce a pose; equal weights give the mid rotation and the mean translation', () => {
  const model = readAnimatedModel(createRiggedFigure().document);
  const a = createRestPose(model);
  const b = createRestPose(model);
  const n = model.nodes.findIndex((node) => node.name === 'Spine');
  const axis = [0, 0.6, 0.8] as const;
  a.rotations.set(axisAngleQuaternion(axis, 20), 4 * n);
  b.rotations.set(axisAngleQuaternion(axis, 80).map((v) => -v), 4 * n); // opposite sign, same rotation
  a.translations.set([1, 2, 3], 3 * n);
  b.translations.set([3, 2, -1], 3 * n);
  b.scales.set([2, 2, 2], 3 * n);
  const out = createRestPose(model);
  blendPoses([{ pose: a, weight: 1 }, { pose: b, weight: 0 }], out);
  assertClose(out.translations, a.translations, 0, 'weight 1/0');
  assertSameRotation(out.rotations.subarray(4 * n, 4 * n + 4), axisAngleQuaternion(axis, 20), 1e-15);
  blendPoses([{ pose: a, weight: 3 }, { pose: b, weight: 3 }], out);
  assertClose(out.translations.subarray(3 * n, 3 * n + 3), [2, 2, 1], 1e-15, 'mean translation');
  assertClose(out.scales.subarray(3 * n, 3 * n + 3), [1.5, 1.5, 1.5], 1e-15, 'mean scale');
  // Equal-weight nlerp of two rotations about one axis is exactly the half-angle rotation.
  assertSameRotation(out.rotations.subarray(4 * n, 4 * n + 4), axisAngleQuaternion(axis, 50), 1e-12, 'mid rotation');
  // Unequal weights stay on the same arc (rotation about the same axis, angle between 20 and 80).
  blendPoses([{ pose: a, weight: 0.25 }, { pose: b, weight: 0.75 }], out);
  const q = out.rotations.subarray(4 * n, 4 * n + 4);
  const s = Math.hypot(q[0], q[1], q[2]);
  assertClose([q[0] / s, q[1] / s, q[2] / s].map((v) => v * Math.sign(q[3])), axis, 1e-12, 'same axis');
  const angle = (2 * Math.atan2(s, Math.abs(q[3])) * 180) / Math.PI;
  assert.ok(angle > 50 && angle < 80, `angle ${angle}`);
});

test('joint matrices are identity in the bind pose, whatever the skinned mesh node transform', () => {
  const model = readAnimatedModel(createRiggedFigure().document);
  const world = computeWorldMatrices(model, createRestPose(model));
  const joints = computeJointMatrices(model, 0, world);
  for (let j = 0; j < model.skins[0].joints.length; j++) assertClose(joints.subarray(16 * j, 16 * j + 16), mat4d.identity(), 1e-6, `joint ${j}`);
  // The Body node is translated by (5, 0, 0); glTF 2.0 section 3.7.3.1 says to ignore it for skinning.
  const body = model.nodes.find((n) => n.name === 'Body')!;
  assert.deepEqual([...body.translation], [5, 0, 0]);
});
