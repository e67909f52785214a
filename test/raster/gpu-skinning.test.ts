// GPU skinning (skin.wesl) against the CPU reference (src/animation/skinning): morph targets then
// 4- or 8-influence linear blend skinning of the rigged test figure in a pose with non-uniform joint
// scale, read back from the GPU and compared vertex by vertex.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readAnimatedModel } from '../../src/animation/model/read-model.ts';
import { evaluateClipPose } from '../../src/animation/pose/evaluate-clip.ts';
import { computeJointMatrices, computeWorldMatrices } from '../../src/animation/pose/world-matrices.ts';
import { applyMorphTargets } from '../../src/animation/skinning/morph-targets.ts';
import { skinVertices } from '../../src/animation/skinning/skin-vertices.ts';
import { skinnedMeshFromPrimitive } from '../../src/raster/animated/model-meshes.ts';
import { createRasterRenderer } from '../../src/raster/index.ts';
import { createRiggedFigure } from '../animation/fixtures/rigged-figure.ts';
import { testDevice } from '../helpers/gpu.ts';

function assertCloseArrays(actual: Float32Array, expected: ArrayLike<number>, tolerance: number, label: string): void {
  assert.equal(actual.length, expected.length, `${label} length`);
  for (let i = 0; i < expected.length; i++) {
    assert.ok(Math.abs(actual[i]! - expected[i]!) <= tolerance, `${label}[${i}]: GPU ${actual[i]} vs CPU ${expected[i]}`);
  }
}

for (const eightInfluences of [false, true]) {
  test(`GPU-skinned and morphed vertices equal the CPU reference (${eightInfluences ? 8 : 4} influences)`, async () => {
    const model = readAnimatedModel(createRiggedFigure({ eightInfluences }).document);
    const body = model.drawables.find((d) => d.skin >= 0)!;
    const primitive = model.meshes[body.mesh]!.primitives[0]!;
    const pose = evaluateClipPose(model, model.clips[0]!, 0.3);
    // Non-uniform joint scales, so normals need the inverse transpose; a morph weight on the top ring.
    pose.scales.set([1.6, 0.5, 1.1], 3 * model.nodes.findIndex((n) => n.name === 'Spine'));
    pose.scales.set([0.7, 1.3, 2.0], 3 * model.nodes.findIndex((n) => n.name === 'Head'));
    const joints = computeJointMatrices(model, 0, computeWorldMatrices(model, pose));
    const morphWeight = 0.7;
    const cpu = skinVertices(primitive, applyMorphTargets(primitive, [morphWeight]), joints);
    const renderer = await createRasterRenderer({
      device: await testDevice(),
      width: 4,
      height: 4,
      msaa: 1,
      shadow: false,
      materials: [{}],
      skinnedMeshes: [skinnedMeshFromPrimitive(primitive, model.skins[0]!.joints.length, 0)],
    });
    renderer.setSkinPose(0, Float32Array.from(joints), [morphWeight]);
    const stats = await renderer.render();
    assert.equal(stats.skinnedVertices, primitive.vertexCount);
    const gpu = await renderer.readSkinnedVertices(0);
    renderer.destroy();
    // f32 on the GPU against f64 on the CPU: coordinates are O(1).
    assertCloseArrays(gpu.positions, cpu.positions, 2e-5, 'position');
    assertCloseArrays(gpu.normals!, cpu.normals!, 2e-5, 'normal');
    assertCloseArrays(gpu.tangents!, cpu.tangents!, 2e-5, 'tangent');
  });
}
