import { test } from 'node:test';
import assert from 'node:assert/strict';
import { mat4d, vec3d } from 'wgpu-matrix';
import { readAnimatedModel } from '../../src/animation/model/read-model.ts';
import type { AnimatedModel, ModelPrimitive } from '../../src/animation/model/model-types.ts';
import { evaluateClipPose } from '../../src/animation/pose/evaluate-clip.ts';
import { createRestPose, type Pose } from '../../src/animation/pose/pose.ts';
import { computeJointMatrices, computeWorldMatrices } from '../../src/animation/pose/world-matrices.ts';
import { applyMorphTargets } from '../../src/animation/skinning/morph-targets.ts';
import { skinVertices } from '../../src/animation/skinning/skin-vertices.ts';
import { createRiggedFigure, LEVEL_HEIGHTS, SMILE_NORMAL_DELTA, SMILE_POSITION_DELTA } from './fixtures/rigged-figure.ts';
import { assertClose, assertNear } from './helpers.ts';

function bodyPrimitive(model: AnimatedModel): ModelPrimitive {
  return model.meshes.find((m) => m.name === 'Body')!.primitives[0];
}

/** A walk pose with non-uniform scale on two joints, so normals need the true inverse transpose. */
function squashedWalkPose(model: AnimatedModel, t: number): Pose {
  const pose = evaluateClipPose(model, model.clips[0], t);
  const spine = model.nodes.findIndex((n) => n.name === 'Spine');
  const head = model.nodes.findIndex((n) => n.name === 'Head');
  pose.scales.set([1.6, 0.5, 1.1], 3 * spine);
  pose.scales.set([0.7, 1.3, 2.0], 3 * head);
  return pose;
}

function jointMatricesFor(model: AnimatedModel, pose: Pose): Float64Array {
  return computeJointMatrices(model, 0, computeWorldMatrices(model, pose));
}

/** Independent reference: transform the vertex by each joint separately and blend the results. */
function referencePosition(primitive: ModelPrimitive, joints: Float64Array, position: ArrayLike<number>, v: number): number[] {
  const out = [0, 0, 0];
  for (let k = 0; k < primitive.influences; k++) {
    const w = primitive.weights![primitive.influences * v + k];
    const j = primitive.joints![primitive.influences * v + k];
    const p = vec3d.transformMat4([position[3 * v], position[3 * v + 1], position[3 * v + 2]], joints.subarray(16 * j, 16 * j + 16));
    for (let c = 0; c < 3; c++) out[c] += w * p[c];
  }
  return out;
}

/** Independent reference normal: blend 4x4 matrices, invert, transpose, apply to the direction. */
function referenceNormal(primitive: ModelPrimitive, joints: Float64Array, normal: ArrayLike<number>, v: number): number[] {
  let blended = new Float64Array(16);
  for (let k = 0; k < primitive.influences; k++) {
    const w = primitive.weights![primitive.influences * v + k];
    const j = primitive.joints![primitive.influences * v + k];
    blended = mat4d.add(blended, mat4d.multiplyScalar(joints.subarray(16 * j, 16 * j + 16), w));
  }
  const inverseTranspose = mat4d.transpose(mat4d.inverse(blended));
  const n = vec3d.transformMat4Upper3x3([normal[3 * v], normal[3 * v + 1], normal[3 * v + 2]], inverseTranspose);
  return [...vec3d.normalize(n)];
}

for (const eightInfluences of [false, true]) {
  test(`skinned positions and normals equal per-joint and inverse-transpose references (${eightInfluences ? 8 : 4} influences)`, () => {
    const model = readAnimatedModel(createRiggedFigure({ eightInfluences }).document);
    const primitive = bodyPrimitive(model);
    for (const t of [0.1, 0.45, 0.9]) {
      const joints = jointMatricesFor(model, squashedWalkPose(model, t));
      const morphed = applyMorphTargets(primitive, [0]);
      const skinned = skinVertices(primitive, morphed, joints);
      for (let v = 0; v < primitive.vertexCount; v++) {
        assertClose(skinned.positions.subarray(3 * v, 3 * v + 3), referencePosition(primitive, joints, primitive.positions, v), 1e-12, `position ${v} at ${t}`);
        assertClose(skinned.normals!.subarray(3 * v, 3 * v + 3), referenceNormal(primitive, joints, primitive.normals!, v), 1e-9, `normal ${v} at ${t}`);
        assertNear(Math.hypot(...skinned.tangents!.subarray(4 * v, 4 * v + 3)), 1, 1e-12, 'unit tangent');
        assert.equal(skinned.tangents![4 * v + 3], primitive.tangents![4 * v + 3], 'bitangent sign kept');
      }
    }
  });
}

test('skinned normals stay perpendicular to skinned surface edges under non-uniform scale', () => {
  const model = readAnimatedModel(createRiggedFigure().document);
  const primitive = bodyPrimitive(model);
  const joints = jointMatricesFor(model, squashedWalkPose(model, 0.3));
  const skinned = skinVertices(primitive, applyMorphTargets(primitive, [0]), joints);
  // The top ring is weighted to Head only, so its edges move by one matrix (joint 2) and the
  // normal must stay orthogonal to them.
  const top = LEVEL_HEIGHTS.length - 1;
  let checked = 0;
  for (let face = 0; face < 4; face++) {
    const a = face * LEVEL_HEIGHTS.length * 2 + 2 * top;
    const b = a + 1;
    const edge = [0, 1, 2].map((c) => skinned.positions[3 * b + c] - skinned.positions[3 * a + c]);
    const n = skinned.normals!.subarray(3 * a, 3 * a + 3);
    assertNear(edge[0] * n[0] + edge[1] * n[1] + edge[2] * n[2], 0, 1e-12, `face ${face} edge . normal`);
    const naive = vec3d.normalize(vec3d.transformMat4Upper3x3(primitive.normals!.subarray(3 * a, 3 * a + 3), joints.subarray(32, 48)));
    const naiveDot = edge[0] * naive[0] + edge[1] * naive[1] + edge[2] * naive[2];
    if (Math.abs(naiveDot) > 1e-3) checked++;
  }
  assert.ok(checked > 0, 'the squashed pose is non-uniform enough that the plain matrix would tilt some normal');
});

test('morph targets are applied before skinning: rest pose shows base + weight x delta', () => {
  const model = readAnimatedModel(createRiggedFigure().document);
  const primitive = bodyPrimitive(model);
  const joints = jointMatricesFor(model, createRestPose(model));
  const w = 0.6;
  const skinned = skinVertices(primitive, applyMorphTargets(primitive, [w]), joints);
  for (let v = 0; v < primitive.vertexCount; v++) {
    const top = Math.abs(primitive.positions[3 * v + 1] - 2) < 1e-6;
    const base = primitive.positions.subarray(3 * v, 3 * v + 3);
    const expected = [0, 1, 2].map((c) => base[c] + (top ? w * SMILE_POSITION_DELTA[c] : 0));
    assertClose(skinned.positions.subarray(3 * v, 3 * v + 3), expected, 1e-6, `vertex ${v}`);
    if (top) {
      const n = [0, 1, 2].map((c) => primitive.normals![3 * v + c] + w * SMILE_NORMAL_DELTA[c]);
      const length = Math.hypot(...n);
      assertClose(skinned.normals!.subarray(3 * v, 3 * v + 3), n.map((x) => x / length), 1e-6, `normal ${v}`);
    }
  }
  // Walking pose: the morphed point is skinned like any other point.
  const walkJoints = jointMatricesFor(model, evaluateClipPose(model, model.clips[0], 0.6));
  const morphed = applyMorphTargets(primitive, [1]);
  const walked = skinVertices(primitive, morphed, walkJoints);
  for (let v = 0; v < primitive.vertexCount; v++) {
    assertClose(walked.positions.subarray(3 * v, 3 * v + 3), referencePosition(primitive, walkJoints, morphed.positions, v), 1e-12, `walk vertex ${v}`);
  }
});

test('mirrored joints keep normals on the inverse transpose (sign of the determinant); collapsed joints stay finite', () => {
  const model = readAnimatedModel(createRiggedFigure().document);
  const primitive = bodyPrimitive(model);
  const pose = evaluateClipPose(model, model.clips[0], 0.4);
  const head = model.nodes.findIndex((n) => n.name === 'Head');
  pose.scales.set([-1, 1.2, 0.8], 3 * head);
  const joints = jointMatricesFor(model, pose);
  const skinned = skinVertices(primitive, applyMorphTargets(primitive, [0]), joints);
  for (let v = 0; v < primitive.vertexCount; v++) {
    assertClose(skinned.normals!.subarray(3 * v, 3 * v + 3), referenceNormal(primitive, joints, primitive.normals!, v), 1e-9, `mirrored normal ${v}`);
  }
  pose.scales.set([0, 0, 0], 3 * head);
  const collapsed = skinVertices(primitive, applyMorphTargets(primitive, [0]), jointMatricesFor(model, pose));
  for (const value of [...collapsed.positions, ...collapsed.normals!, ...collapsed.tangents!]) assert.ok(Number.isFinite(value));
});
