// A geometry update that only moves instances patches their top-level records
// (pathtracer/scene/top-level-patch.ts) instead of flattening the scene again. The patched buffer
// must be bit for bit what the full path (flattenPrimitives + packPrimitives in the uploaded order)
// writes for the moved scene: flattened instances (mirrored, single-sided, alpha-masked, emissive),
// placements of shared meshes and analytic shapes, in either build mode's order.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { packPrimitives } from '../../src/accel/triangle-packing.ts';
import { terminateBvhWorkers } from '../../src/accel/bvh-builder.ts';
import { packGeometryUpdate, type WavefrontGeometryUpdate } from '../../src/pathtracer/scene/geometry-update.ts';
import { flattenPrimitives } from '../../src/pathtracer/scene/flatten-primitives.ts';
import { bottomLevelRoots, type InstancingMode } from '../../src/pathtracer/scene/instancing.ts';
import { prepareGeometry, prepareMaterials, type AccelerationBuildMode } from '../../src/pathtracer/scene/prepare-scene.ts';
import { applyTopLevelPatch } from '../../src/pathtracer/scene/top-level-patch.ts';
import { normalizeWavefrontScene } from '../../src/scene/normalize-scene.ts';
import type { WavefrontSceneDescription } from '../../src/scene/types.ts';
import { icosphere } from '../helpers/meshes.ts';
import { transformsCamera, transformsScene, trs } from './instancing-scenes.ts';

test.after(() => terminateBvhWorkers());

/** The transforms scene, a denser sphere placed twice ('auto' shares it, nothing else) and two analytic shapes. */
function scene(): WavefrontSceneDescription {
  const s = transformsScene();
  const dense = { ...icosphere(0.3, [0, 0, 0], 3), material: { baseColorFactor: [0.7, 0.7, 0.75] as [number, number, number], metallicFactor: 1, roughnessFactor: 0.3 } };
  return {
    ...s,
    meshes: [...s.meshes, dense],
    instances: [...s.instances, { mesh: 5, transform: trs([0, 0.3, -1.8], [0, 1, 0], 0.2, [1, 1, 1]) }, { mesh: 5, transform: trs([1.8, 0.3, -1.2], [1, 0, 0], 0.5, [1.2, 0.8, -1]) }],
    sceneObjects: [{ type: 'sphere', center: [-2, 0.4, -2], radius: 0.4 }, { type: 'box', min: [2, 0, 2], max: [2.5, 0.5, 2.6] }],
    camera: transformsCamera,
  };
}

/**
 * Frame k of a move: instances with odd indices (alpha-masked, emissive, shared and not) turned,
 * shifted and rescaled; instance 3 stops being mirrored, instance 5 starts.
 */
function moveOdd(instances: number, k: number): WavefrontGeometryUpdate {
  return {
    instances: Array.from({ length: instances }, (_, i) => (i % 2 === 1 ? { transform: trs([0.1 * k, 0.05 * i, -0.07 * k], [0, 1, 0], 0.3 * k + 0.1 * i, [1 + 0.1 * k, 1, i === 5 ? -0.9 : 0.8]) } : null)),
  };
}

for (const instancing of ['auto', 'off', 'always'] as InstancingMode[]) {
  for (const accelerationBuildMode of ['cpu-upload', 'gpu'] as AccelerationBuildMode[]) {
    test(`moved instances patch the records the full path writes (instancing '${instancing}', ${accelerationBuildMode})`, async () => {
      const normalized = normalizeWavefrontScene(scene());
      const materials = prepareMaterials(normalized, { maxTextureDimension2D: 4096, maxTextureArrayLayers: 64 });
      const prepared = await prepareGeometry(normalized, materials, { instancing, accelerationBuildMode });
      const placements = prepared.instancing.bottomLevels.length;
      if (instancing === 'auto') assert.equal(placements, 1, "'auto' shares the dense sphere only");
      if (instancing === 'off') assert.equal(placements, 0);
      let current = normalized;
      for (let k = 1; k <= 3; k++) {
        const packed = packGeometryUpdate(current, prepared, moveOdd(normalized.instances.length, k));
        assert.ok(packed.topLevel.patch, 'a refit that moves instances only is a patch');
        const before = new Uint8Array(prepared.primitives.slice(0));
        const { first, end } = applyTopLevelPatch(prepared, packed.topLevel.patch);
        current = packed.scene;
        // The full path for the same moved scene, in the same order.
        const flat = flattenPrimitives(current, materials.infoOffset, prepared.instancing, prepared.bottomLevels ? bottomLevelRoots(prepared.bottomLevels) : null);
        const order = prepared.acceleration.order ?? Uint32Array.from({ length: flat.count }, (_, i) => i);
        const want = new Uint8Array(packPrimitives(flat, order));
        const got = new Uint8Array(prepared.primitives);
        assert.equal(got.length, want.length);
        const differing = want.findIndex((b, i) => b !== got[i]);
        assert.equal(differing, -1, `frame ${k}: byte ${differing} (record ${Math.floor(differing / 64)}) differs from the full path`);
        assert.deepEqual(new Uint8Array(prepared.placementTransforms.records), new Uint8Array(flat.placementTransforms));
        assert.deepEqual(packed.bounds, flat.bounds);
        assert.deepEqual(prepared.instanceBounds, flat.instanceBounds);
        // The upload range covers every changed byte.
        const size = got.length / Math.max(1, flat.count);
        for (let i = 0; i < got.length; i++) {
          if (got[i] !== before[i]) assert.ok(i >= first * size && i < end * size, `changed byte ${i} outside the uploaded slots [${first}, ${end})`);
        }
        assert.ok(end > first, 'something moved');
      }
    });
  }
}

test('a rebuild or moved meshes take the full path', async () => {
  const normalized = normalizeWavefrontScene(scene());
  const materials = prepareMaterials(normalized, { maxTextureDimension2D: 4096, maxTextureArrayLayers: 64 });
  const prepared = await prepareGeometry(normalized, materials, { instancing: 'auto' });
  const move = moveOdd(normalized.instances.length, 1);
  assert.ok(packGeometryUpdate(normalized, prepared, { ...move, bvh: 'rebuild' }).topLevel.flat);
  const grown = { positions: Array.from(normalized.meshes[5]!.positions, (v) => 1.05 * v) };
  assert.ok(packGeometryUpdate(normalized, prepared, { ...move, meshes: normalized.meshes.map((_, i) => (i === 5 ? grown : null)) }).topLevel.flat);
});
