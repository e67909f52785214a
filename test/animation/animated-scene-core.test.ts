import { test } from 'node:test';
import assert from 'node:assert/strict';
import { Document } from '@gltf-transform/core';
import { createAnimatedSceneCore, type AnimatedSceneCoreOptions } from '../../src/animation/animated-scene-core.ts';
import { applyMorphTargets } from '../../src/animation/skinning/morph-targets.ts';
import { skinVertices } from '../../src/animation/skinning/skin-vertices.ts';
import { FIGURE_CLIP_ASSETS } from './fixtures/figure-library.ts';
import { createRiggedFigure, HALF_DEPTH, HALF_WIDTH, JOINT_NAMES, LEVEL_HEIGHTS } from './fixtures/rigged-figure.ts';
import { assertClose, assertNear, expectRendererError } from './helpers.ts';

const terrain = (x: number, z: number): number => 0.02 * x - 0.01 * z;
function options(overrides: Partial<AnimatedSceneCoreOptions> = {}): AnimatedSceneCoreOptions {
  return {
    modelAsset: createRiggedFigure().document,
    clipAssets: FIGURE_CLIP_ASSETS,
    beats: [
      { id: 'walk-in', order: 0, clipId: 'walk', durationMs: 3000, blend: { outMs: 250 }, movementRequirement: { kind: 'travel', distance: 3 } },
      { id: 'look-around', order: 1, clipId: 'idle', durationMs: 2000, blend: { inMs: 250 }, movementRequirement: { kind: 'stationary' } },
    ],
    route: [{ position: [0, terrain(0, 0), 0], arriveMs: 0 }, { position: [0, terrain(0, 3), 3], arriveMs: 3000 }],
    props: [{ kind: 'barrel', position: [1, 0, 2] }],
    camera: { lagMs: 150, constraints: { minDistance: 2, maxDistance: 6 } },
    terrain,
    ...overrides,
  };
}

test('snapshots carry the renderer-independent fields', () => {
  const scene = createAnimatedSceneCore(options());
  assert.equal(scene.getSnapshot(), null);
  scene.frame(0);
  const s = scene.frame(1500).snapshot;
  assert.equal(s.frame, 2);
  assert.equal(s.timeMs, 1500);
  assert.equal(s.activeBeatId, 'walk-in');
  assert.equal(s.activeClipId, 'walk');
  assertNear(s.clipTimeMs, 500, 1e-9, 'clip time');
  assert.equal(s.blendProgress, 1);
  assertClose(s.characterPosition, [0, terrain(0, 1.5), 1.5], 1e-12, 'character on the route and the ground');
  assert.equal(s.characterGroundY, terrain(0, 1.5));
  // Independent counts from the fixture's construction: 4 faces x levels x 2 edge vertices; 5 joints.
  assert.equal(s.skinnedVertexCount, 4 * LEVEL_HEIGHTS.length * 2);
  assert.equal(s.skinnedJointCount, JOINT_NAMES.length);
  assert.equal(s.cameraViewMode, 'third-person');
  assert.deepEqual(s.cameraPosition, s.cameraTransform.position);
  assert.ok(s.targetDistance >= 2 && s.targetDistance <= 6);
  assert.equal(s.headLook.active, false);
  assert.deepEqual(s.propGroundAnchors.map((p) => [p.kind, ...p.position]), [['barrel', 1, terrain(1, 2), 2]]);
  assert.equal(s.movementValidation.valid, true, JSON.stringify(s.movementValidation.diagnostics));
  assert.equal(s.fallbackProxyActive, false);
  assert.equal(scene.getSnapshot(), s);
  const blending = scene.frame(3100).snapshot;
  assert.equal(blending.activeBeatId, 'look-around');
  assertNear(blending.blendProgress, (3100 - 2750) / 500, 1e-12, 'cross-fade progress');
});

test('camera calls route to the rigs and show up in the snapshot', () => {
  const scene = createAnimatedSceneCore(options());
  scene.setCameraViewMode('first-person');
  scene.applyCameraControl({ look: [0.3, 0] });
  const s = scene.frame(1000).snapshot;
  assert.equal(s.cameraViewMode, 'first-person');
  assert.equal(s.headLook.yaw, 0.3);
  assertNear(s.targetDistance, 0, 0, 'first person');
  scene.setCamera({ viewMode: 'third-person', offset: [0, 0, -50] });
  assertNear(scene.frame(1000).snapshot.targetDistance, 6, 1e-12, 'offset clamped to maxDistance');
});

test('the raster inputs of a frame (joint matrices, morph weights) skin to the same vertices as the baked path-tracer still', () => {
  const scene = createAnimatedSceneCore(options());
  for (const t of [700, 2900, 3600]) {
    const frame = scene.frame(t);
    const baked = scene.bakePose(t);
    const d = scene.model.drawables.findIndex((x) => x.skin >= 0);
    const drawable = scene.model.drawables[d];
    const primitive = scene.model.meshes[drawable.mesh].primitives[0];
    const skinned = skinVertices(primitive, applyMorphTargets(primitive, frame.morphWeights[d]), Float64Array.from(frame.jointMatrices[drawable.skin]));
    const mesh = baked.meshes.find((m) => m.id === `node${drawable.node}.mesh${drawable.mesh}.primitive0`)!;
    assertClose(skinned.positions, mesh.positions, 1e-5, `positions at ${t}`);
    const instance = baked.instances.find((i) => i.id === mesh.id)!;
    assertClose(instance.transform!, frame.sample.rootTransform, 0, 'placement');
  }
});

test('the professional path fails closed on missing textures, non-skinned models and travel clips without root motion', () => {
  createAnimatedSceneCore(options({ professional: true }));
  const noNormalMap = createRiggedFigure({ omitNormalTexture: true }).document;
  const skinMaterial = noNormalMap.getRoot().listMaterials().findIndex((m) => m.getName() === 'Skin');
  expectRendererError(() => createAnimatedSceneCore(options({ modelAsset: noNormalMap, professional: true })), 'INVALID_MODEL', `modelAsset.materials[${skinMaterial}].normalTexture`);
  createAnimatedSceneCore(options({ modelAsset: createRiggedFigure({ omitNormalTexture: true }).document }));
  const noUvs = createRiggedFigure().document;
  const bodyIndex = noUvs.getRoot().listMeshes().findIndex((m) => m.getName() === 'Body');
  noUvs.getRoot().listMeshes()[bodyIndex].listPrimitives()[0].setAttribute('TEXCOORD_0', null);
  expectRendererError(() => createAnimatedSceneCore(options({ modelAsset: noUvs, professional: true })), 'INVALID_MODEL', `modelAsset.meshes[${bodyIndex}].primitives[0].attributes.TEXCOORD_0`);
  const travelWith = (clipId: string): AnimatedSceneCoreOptions => {
    const o = options({ professional: true });
    return { ...o, beats: [{ ...o.beats[0], clipId }, ...o.beats.slice(1)] };
  };
  expectRendererError(() => createAnimatedSceneCore(travelWith('idle')), 'INVALID_ANIMATION', 'clipAssets[1].movementProfile.rootMotion');
  expectRendererError(() => createAnimatedSceneCore(travelWith('idle-no-profile')), 'INVALID_ANIMATION', 'clipAssets[4].movementProfile');
  // A model without a skin is not a character, professional or not.
  const statue = new Document();
  statue.createBuffer();
  const mesh = statue.createMesh('Statue').addPrimitive(statue.createPrimitive().setAttribute('POSITION', statue.createAccessor().setType('VEC3').setArray(new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0]))));
  statue.createScene().addChild(statue.createNode('Statue').setMesh(mesh));
  expectRendererError(() => createAnimatedSceneCore(options({ modelAsset: statue, clipAssets: undefined })), 'INVALID_MODEL', 'modelAsset.skins');
  expectRendererError(() => createAnimatedSceneCore(options({ modelAsset: {} as Document })), 'INVALID_OPTION', 'modelAsset');
});

test('the figure fixture really is the described box tube', () => {
  const scene = createAnimatedSceneCore(options());
  const body = scene.model.meshes.find((m) => m.name === 'Body')!.primitives[0];
  for (let v = 0; v < body.vertexCount; v++) {
    assertNear(Math.abs(body.positions[3 * v]), HALF_WIDTH, 1e-7, 'x on a side');
    assertNear(Math.abs(body.positions[3 * v + 2]), HALF_DEPTH, 1e-7, 'z on a side');
  }
});
