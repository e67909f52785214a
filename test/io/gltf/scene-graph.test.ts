import { test } from 'node:test';
import assert from 'node:assert/strict';
import { Document } from '@gltf-transform/core';
import { EXTMeshGPUInstancing, KHRLightsPunctual, KHRMaterialsVariants, KHRNodeVisibility } from '@gltf-transform/extensions';
import { loadGltfScene } from '../../../src/io/index.ts';
import { frameBounds } from '../../../src/scene/camera-framing.ts';
import {
  accessor,
  assertClose,
  columnMajor,
  mulRows,
  quadMesh,
  quat,
  rejectsWith,
  rotationXRows,
  rotationZRows,
  scaleRows,
  toGlb,
  toGltfJsonBytes,
  translationRows,
} from './helpers.ts';

test('node hierarchy: world matrices, shared meshes as instances, negative scale', async () => {
  const doc = new Document();
  const buffer = doc.createBuffer();
  const shared = quadMesh(doc, buffer, undefined, 'shared');
  const parent = doc.createNode('parent').setTranslation([1, 2, 3]).setRotation(quat([0, 0, 1], Math.PI / 2)).setScale([2, 2, 2]);
  const child = doc.createNode('child').setTranslation([0.5, 0, 0]).setRotation(quat([1, 0, 0], Math.PI / 3)).setMesh(shared);
  const mirrored = doc.createNode('mirrored').setScale([-1, 1, 1]).setTranslation([0, -4, 0]).setMesh(shared);
  parent.addChild(child);
  doc.createScene('main').addChild(parent).addChild(mirrored);
  const scene = await loadGltfScene(await toGlb(doc));

  assert.equal(scene.meshes.length, 1, 'one primitive = one mesh entry, shared by both nodes');
  assert.equal(scene.instances.length, 2);
  assert.ok(scene.instances.every((i) => i.mesh === 0));
  const expectedChild = mulRows(translationRows([1, 2, 3]), rotationZRows(Math.PI / 2), scaleRows([2, 2, 2]), translationRows([0.5, 0, 0]), rotationXRows(Math.PI / 3));
  const expectedMirror = mulRows(translationRows([0, -4, 0]), scaleRows([-1, 1, 1]));
  const byId = new Map(scene.instances.map((i) => [i.id, i]));
  assertClose(byId.get('child')!.transform!, columnMajor(expectedChild), 1e-6, 'child');
  assertClose(byId.get('mirrored')!.transform!, columnMajor(expectedMirror), 1e-12, 'mirrored');
  // The negative scale survives: the linear part has determinant -1 (winding flip for the renderer).
  const m = byId.get('mirrored')!.transform!;
  const det = m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) + m[8] * (m[1] * m[6] - m[5] * m[2]);
  assert.ok(Math.abs(det + 1) < 1e-12, `determinant ${det}`);

  // Bounds: the quad's corners through both transforms, computed independently.
  const corners = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]];
  const min = [Infinity, Infinity, Infinity];
  const max = [-Infinity, -Infinity, -Infinity];
  for (const rows of [expectedChild, expectedMirror]) {
    for (const c of corners) {
      const p = [0, 1, 2].map((r) => rows[r][0] * c[0] + rows[r][1] * c[1] + rows[r][2] * c[2] + rows[r][3]);
      p.forEach((v, k) => ((min[k] = Math.min(min[k], v)), (max[k] = Math.max(max[k], v))));
    }
  }
  assertClose(scene.bounds!.min, min, 1e-6, 'bounds.min');
  assertClose(scene.bounds!.max, max, 1e-6, 'bounds.max');
});

test('a node given as a matrix keeps that matrix, negative determinant included', async () => {
  const doc = new Document();
  const mesh = quadMesh(doc, doc.createBuffer());
  const rows = mulRows(translationRows([3, 0, -1]), rotationZRows(0.7), scaleRows([1, -2, 0.5]));
  const node = doc.createNode('m').setMesh(mesh);
  doc.createScene().addChild(node);
  const json = JSON.parse(new TextDecoder().decode(await toGltfJsonBytes(doc)));
  delete json.nodes[0].translation;
  delete json.nodes[0].rotation;
  delete json.nodes[0].scale;
  json.nodes[0].matrix = columnMajor(rows);
  const scene = await loadGltfScene(new TextEncoder().encode(JSON.stringify(json)));
  assertClose(scene.instances[0].transform!, columnMajor(rows), 1e-6, 'matrix node');
});

test('result: only renderer keys are enumerable; metadata is non-enumerable', async () => {
  const doc = new Document();
  doc.createScene().addChild(doc.createNode('n').setMesh(quadMesh(doc, doc.createBuffer())));
  const scene = await loadGltfScene(await toGlb(doc));
  assert.deepEqual(Object.keys(scene).sort(), ['camera', 'images', 'instances', 'lights', 'materials', 'meshes', 'textures']);
  const spread = { ...scene };
  assert.equal('warnings' in spread, false);
  for (const key of ['warnings', 'cameras', 'variants', 'bounds', 'extensionsUsed', 'document']) {
    const d = Object.getOwnPropertyDescriptor(scene, key);
    assert.ok(d !== undefined && d.enumerable === false, key);
  }
  // A primitive without a material gets the glTF default material.
  assert.equal(scene.materials.length, 1);
  assert.deepEqual(scene.materials[0], { name: 'glTF default material', baseColorFactor: [1, 1, 1, 1], metallicFactor: 1, roughnessFactor: 1, emissiveFactor: [0, 0, 0], alphaMode: 'OPAQUE', doubleSided: false });
  assert.equal(scene.meshes[0].material, 0);
});

test('cameras: perspective and orthographic from node world matrices; selection by index and name', async () => {
  const doc = new Document();
  const main = doc.createScene().addChild(doc.createNode('geometry').setMesh(quadMesh(doc, doc.createBuffer())));
  const persp = doc.createCamera('wide').setType('perspective').setYFov(0.8).setZNear(0.1).setAspectRatio(2);
  const ortho = doc.createCamera('plan').setType('orthographic').setYMag(3).setXMag(3).setZNear(0).setZFar(10);
  // Perspective camera: rotated 90 degrees about +Y (looks down -X), under a translated parent.
  const rig = doc.createNode('rig').setTranslation([0, 1, 0]);
  const eye = doc.createNode('eye').setTranslation([5, 0, 0]).setRotation(quat([0, 1, 0], Math.PI / 2)).setCamera(persp);
  rig.addChild(eye);
  // Orthographic camera looking straight down (-Y): rotate -90 degrees about X.
  const top = doc.createNode('top').setTranslation([0, 10, 0]).setRotation(quat([1, 0, 0], -Math.PI / 2)).setCamera(ortho);
  main.addChild(rig).addChild(top);
  const glb = await toGlb(doc);

  const scene = await loadGltfScene(glb);
  assert.equal(scene.cameras.length, 2);
  const c = scene.camera;
  assert.equal(c.type, 'perspective');
  assertClose(c.position, [5, 1, 0], 1e-6, 'position');
  // Rotating -Z by +90 degrees about +Y gives -X.
  assertClose(c.target, [4, 1, 0], 1e-6, 'target');
  assertClose(c.up!, [0, 1, 0], 1e-6, 'up');
  assert.ok(Math.abs(c.fovYDegrees! - (0.8 * 180) / Math.PI) < 1e-4);

  for (const choice of [1, 'top', 'plan']) {
    const s = await loadGltfScene(glb, { camera: choice });
    assert.equal(s.camera.type, 'orthographic', String(choice));
    assert.equal(s.camera.orthographicHeight, 6);
    assertClose(s.camera.position, [0, 10, 0], 1e-6, 'ortho position');
    assertClose(s.camera.target, [0, 9, 0], 1e-6, 'ortho target');
    assertClose(s.camera.up!, [0, 0, -1], 1e-6, 'ortho up');
  }
  await rejectsWith(loadGltfScene(glb, { camera: 'nope' }), 'INVALID_OPTION', 'camera', /no camera "nope"/);
});

test('no camera: the default camera is a raised three-quarter view fitted to the bounds (frameBounds), for the aspect ratio asked', async () => {
  const doc = new Document();
  const node = doc.createNode('n').setMesh(quadMesh(doc, doc.createBuffer())).setScale([4, 2, 1]).setTranslation([-1, 0, 0]);
  doc.createScene().addChild(node);
  const glb = await toGlb(doc);
  const scene = await loadGltfScene(glb);
  // Bounds [-1, 3] x [0, 2] x [0, 0]: the quad faces +Z; it is looked at from azimuth 30 degrees
  // (towards +X) and elevation 25, not edge-on and not straight on.
  assertClose(scene.camera.target, [1, 1, 0], 1e-9, 'target');
  assert.deepEqual(scene.camera, frameBounds(scene.bounds, { azimuthDegrees: 30, elevationDegrees: 25, fovYDegrees: 45, aspectRatio: 1 }));
  const toEye = scene.camera.position.map((v, i) => v - scene.camera.target[i]);
  const length = Math.hypot(...toEye);
  assertClose(toEye.map((v) => v / length), [Math.sin(Math.PI / 6) * Math.cos((25 * Math.PI) / 180), Math.sin((25 * Math.PI) / 180), Math.cos(Math.PI / 6) * Math.cos((25 * Math.PI) / 180)], 1e-9, 'direction');
  const wide = await loadGltfScene(glb, { aspectRatio: 2 });
  assert.deepEqual(wide.camera, frameBounds(wide.bounds, { aspectRatio: 2 }));
  assert.ok(Math.hypot(...wide.camera.position.map((v, i) => v - wide.camera.target[i])) < length, 'a wider image frames the wide quad from closer');
});

test('KHR_lights_punctual: world position, direction (-Z of the node) and parameters', async () => {
  const doc = new Document();
  const ext = doc.createExtension(KHRLightsPunctual);
  const spot = ext.createLight('spot').setType('spot').setColor([1, 0.5, 0.25]).setIntensity(40).setRange(12).setInnerConeAngle(0.2).setOuterConeAngle(0.5);
  const sun = ext.createLight('sun').setType('directional').setIntensity(3);
  const bulb = ext.createLight('bulb').setType('point').setIntensity(7);
  const parent = doc.createNode('p').setTranslation([0, 2, 0]).setScale([3, 3, 3]);
  // Spot: rotated -90 degrees about X, so -Z maps to -Y (pointing down).
  parent.addChild(doc.createNode('spot').setTranslation([1, 0, 0]).setRotation(quat([1, 0, 0], -Math.PI / 2)).setExtension('KHR_lights_punctual', spot));
  const s = doc.createScene().addChild(parent);
  s.addChild(doc.createNode('sun').setRotation(quat([0, 1, 0], Math.PI / 2)).setExtension('KHR_lights_punctual', sun));
  s.addChild(doc.createNode('bulb').setTranslation([0, 0, 9]).setExtension('KHR_lights_punctual', bulb));
  const scene = await loadGltfScene(await toGlb(doc));
  assert.equal(scene.lights.length, 3);
  const [l0, l1, l2] = scene.lights;
  assert.equal(l0.type, 'spot');
  assertClose(l0.position!, [3, 2, 0], 1e-6, 'spot position');
  assertClose(l0.direction!, [0, -1, 0], 1e-6, 'spot direction (unit despite the scale)');
  assert.deepEqual([l0.intensity, l0.range, l0.name], [40, 12, 'spot']);
  assertClose(l0.color!, [1, 0.5, 0.25], 0, 'color');
  assertClose([l0.innerConeAngle!, l0.outerConeAngle!], [0.2, 0.5], 1e-7, 'cone');
  assert.equal(l1.type, 'directional');
  assertClose(l1.direction!, [-1, 0, 0], 1e-6, 'sun direction');
  assert.equal(l1.position, undefined);
  assert.equal(l2.type, 'point');
  assertClose(l2.position!, [0, 0, 9], 0, 'bulb');
  assert.equal(l2.direction, undefined);
  assert.equal(l2.range, undefined);
});

test('EXT_mesh_gpu_instancing: one instance per element, composed with the node matrix', async () => {
  const doc = new Document();
  const buffer = doc.createBuffer();
  const mesh = quadMesh(doc, buffer);
  const ext = doc.createExtension(EXTMeshGPUInstancing).setRequired(true);
  const translations = new Float32Array([0, 0, 0, 10, 0, 0, 0, 10, 0]);
  const rotations = new Float32Array([...quat([0, 0, 1], 0), ...quat([0, 0, 1], Math.PI / 2), ...quat([0, 0, 1], Math.PI)]);
  const scales = new Float32Array([1, 1, 1, 2, 2, 2, 1, 1, -1]);
  const batch = ext
    .createInstancedMesh()
    .setAttribute('TRANSLATION', accessor(doc, buffer, 'VEC3', translations))
    .setAttribute('ROTATION', accessor(doc, buffer, 'VEC4', rotations))
    .setAttribute('SCALE', accessor(doc, buffer, 'VEC3', scales));
  const node = doc.createNode('forest').setMesh(mesh).setTranslation([0, 0, 5]).setExtension('EXT_mesh_gpu_instancing', batch);
  doc.createScene().addChild(node);
  const scene = await loadGltfScene(await toGlb(doc));
  assert.equal(scene.meshes.length, 1);
  assert.equal(scene.instances.length, 3);
  for (let i = 0; i < 3; i++) {
    const expected = mulRows(translationRows([0, 0, 5]), translationRows([...translations.subarray(i * 3, i * 3 + 3)]), rotationZRows((i * Math.PI) / 2), scaleRows([...scales.subarray(i * 3, i * 3 + 3)]));
    assertClose(scene.instances[i].transform!, columnMajor(expected), 1e-6, `instance ${i}`);
    assert.equal(scene.instances[i].mesh, 0);
  }
});

test('KHR_materials_variants: the variant picks each primitive\'s material; unknown names are typed errors', async () => {
  const doc = new Document();
  const ext = doc.createExtension(KHRMaterialsVariants);
  const red = doc.createMaterial('red').setBaseColorFactor([1, 0, 0, 1]);
  const blue = doc.createMaterial('blue').setBaseColorFactor([0, 0, 1, 1]);
  const gold = doc.createMaterial('gold').setBaseColorFactor([1, 0.8, 0.2, 1]).setMetallicFactor(1);
  const mesh = quadMesh(doc, doc.createBuffer(), red);
  const vBlue = ext.createVariant('Blue');
  const vGold = ext.createVariant('Gold');
  const mappings = ext.createMappingList()
    .addMapping(ext.createMapping().setMaterial(blue).addVariant(vBlue))
    .addMapping(ext.createMapping().setMaterial(gold).addVariant(vGold));
  mesh.listPrimitives()[0].setExtension('KHR_materials_variants', mappings);
  doc.createScene().addChild(doc.createNode('a').setMesh(mesh)).addChild(doc.createNode('b').setMesh(mesh).setTranslation([2, 0, 0]));
  const glb = await toGlb(doc);

  const plain = await loadGltfScene(glb);
  assert.deepEqual(plain.variants, ['Blue', 'Gold']);
  assert.deepEqual(plain.materials.map((m) => m.name), ['red', 'blue', 'gold']);
  assert.equal(plain.meshes[0].material, 0);
  const gilded = await loadGltfScene(glb, { variant: 'Gold' });
  assert.equal(gilded.meshes.length, 1);
  assert.equal(gilded.meshes[0].material, 2);
  assert.equal((await loadGltfScene(glb, { variant: 'Blue' })).meshes[0].material, 1);
  await rejectsWith(loadGltfScene(glb, { variant: 'Green' }), 'INVALID_OPTION', 'variant', /"Green".*"Blue", "Gold"/);
});

test('scene selection, hidden nodes (KHR_node_visibility) and singular transforms', async () => {
  const doc = new Document();
  const vis = doc.createExtension(KHRNodeVisibility);
  const mesh = quadMesh(doc, doc.createBuffer());
  doc.createScene('first').addChild(doc.createNode('one').setMesh(mesh));
  const hidden = doc.createNode('hidden').setExtension('KHR_node_visibility', vis.createVisibility().setVisible(false));
  hidden.addChild(doc.createNode('under-hidden').setMesh(mesh));
  doc.createScene('second')
    .addChild(doc.createNode('two').setMesh(mesh))
    .addChild(doc.createNode('three').setMesh(mesh).setTranslation([3, 0, 0]))
    .addChild(doc.createNode('flat').setMesh(mesh).setScale([1, 0, 1]))
    .addChild(hidden);
  doc.getRoot().setDefaultScene(doc.getRoot().listScenes()[1]);
  const glb = await toGlb(doc);
  const byDefault = await loadGltfScene(glb);
  assert.deepEqual(byDefault.instances.map((i) => i.id), ['two', 'three']);
  assert.ok(byDefault.warnings.some((w) => w.startsWith('/nodes/5') && /singular/.test(w)), byDefault.warnings.join('\n'));
  assert.deepEqual((await loadGltfScene(glb, { scene: 0 })).instances.map((i) => i.id), ['one']);
  assert.deepEqual((await loadGltfScene(glb, { scene: 'first' })).instances.map((i) => i.id), ['one']);
  await rejectsWith(loadGltfScene(glb, { scene: 5 }), 'INVALID_OPTION', 'scene');
});
