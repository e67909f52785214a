// Issue 25: a scene mixing reused nodes and EXT_mesh_gpu_instancing with rotations, non-uniform
// and mirroring scales (fixtures/instanced-transforms/scene.glb, loaded by the public glTF
// loader) agrees block by block with an independent renderer: Mitsuba 3's path tracer rendering
// the world-space triangles that scripts/reference/instanced-transforms-scene.ts flattened from
// the same spec (its own transforms, normals by the inverse transpose, winding reversed under a
// mirror), whose per-block means and standard errors are stored in mitsuba-reference.json
// (scripts/reference/instanced_transforms_mitsuba.py; CI needs no Python). Our maxDepth D is
// Mitsuba's max_depth D + 1. Every material is single-sided and camera rays cull back faces, so
// a mirrored instance rendered with its winding unflipped shows its inside and fails here.
// The statistics: test/helpers/block-reference.ts.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { assertMatchesReference, type BlockReference } from '../helpers/block-reference.ts';
import { testDevice } from '../helpers/gpu.ts';
import { instancedTransformsSpec as spec, readInstancedFixture, renderInstancedTransforms } from './instanced-transforms-scene.ts';

const reference = readInstancedFixture<BlockReference>('mitsuba-reference.json');
// INSTANCED_REFERENCE_SPP renders more.
const spp = Number(process.env.INSTANCED_REFERENCE_SPP ?? 128);

// 'always' traces every placement through a bottom-level tree in object space (the scene's meshes
// are too small for 'auto' to share them); 'off' flattens them into world-space triangles.
for (const instancing of ['always', 'off'] as const) {
  test(`shared meshes placed by reused nodes and EXT_mesh_gpu_instancing (rotations, non-uniform and mirroring scales; instancing '${instancing}') agree with Mitsuba 3 rendering the flattened triangles, block by block (8x8 blocks, Bonferroni) and in the image mean`, async (t) => {
    assert.equal(reference.matchesMaxDepth, spec.maxDepth, 'the reference was rendered at the matching depth');
    assert.equal(reference.blocksX * reference.blocksY, (spec.width / spec.block) * (spec.height / spec.block));
    const ours = await renderInstancedTransforms(await testDevice(), spp, 23, { instancing });
    assert.equal(ours.invalidSamples, 0);
    assertMatchesReference(t, ours, reference, spp);
  });
}
