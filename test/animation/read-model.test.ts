import { test } from 'node:test';
import assert from 'node:assert/strict';
import { NodeIO, Primitive } from '@gltf-transform/core';
import { KHRMeshPrimitiveRestart } from '@gltf-transform/extensions';
import { mat4d } from 'wgpu-matrix';
import { readAnimatedModel } from '../../src/animation/model/read-model.ts';
import { modelRasterParts } from '../../src/raster/animated/model-meshes.ts';
import { createRiggedFigure, JOINT_NAMES, LEVEL_HEIGHTS, figureInfluences } from './fixtures/rigged-figure.ts';
import { assertClose, expectRendererError } from './helpers.ts';

test('reads the node hierarchy with rest transforms, parents before children', () => {
  const { document } = createRiggedFigure();
  const model = readAnimatedModel(document);
  const names = model.nodes.map((n) => n.name);
  for (const name of ['Armature', 'Body', ...JOINT_NAMES, 'Badge']) assert.ok(names.includes(name), name);
  const index = (name: string): number => names.indexOf(name);
  assert.equal(model.nodes[index('Hips')].parent, index('Armature'));
  assert.equal(model.nodes[index('Head')].parent, index('Spine'));
  assert.equal(model.nodes[index('Armature')].parent, -1);
  assert.deepEqual([...model.nodes[index('Hips')].translation], [0, 2, 0]);
  assert.equal(model.nodeOrder.length, model.nodes.length);
  const position = new Map([...model.nodeOrder].map((n, i) => [n, i]));
  model.nodes.forEach((node, i) => {
    if (node.parent >= 0) assert.ok(position.get(node.parent)! < position.get(i)!, `${node.name} after its parent`);
  });
});

test('reads the skin: joints in skin order and inverse bind matrices that undo the rest world matrices', () => {
  const { document, nodes } = createRiggedFigure();
  const model = readAnimatedModel(document);
  assert.equal(model.skins.length, 1);
  const skin = model.skins[0];
  assert.deepEqual([...skin.joints].map((j) => model.nodes[j].name), [...JOINT_NAMES]);
  assert.equal(model.nodes[skin.skeleton].name, 'Hips');
  const jointNodes = [nodes.hips, nodes.spine, nodes.head, nodes.leftLeg, nodes.rightLeg];
  jointNodes.forEach((node, j) => {
    // Independent world matrix: gltf-transform's own scene-graph evaluation.
    const product = mat4d.multiply(Float64Array.from(node.getWorldMatrix()), skin.inverseBindMatrices.subarray(16 * j, 16 * j + 16));
    assertClose(product, mat4d.identity(), 1e-6, `world x inverseBind of ${JOINT_NAMES[j]}`);
  });
});

test('reads vertex streams, normalised 4 or 8 joint influences, the morph target and drawables', () => {
  for (const options of [{}, { eightInfluences: true }, { unnormalisedWeights: true }]) {
    const model = readAnimatedModel(createRiggedFigure(options).document);
    const body = model.meshes[model.nodes.find((n) => n.name === 'Body')!.mesh];
    const primitive = body.primitives[0];
    assert.equal(primitive.vertexCount, 4 * LEVEL_HEIGHTS.length * 2);
    assert.equal(primitive.influences, 'eightInfluences' in options ? 8 : 4);
    assert.ok(primitive.normals && primitive.tangents && primitive.uvs);
    assert.equal(primitive.indices!.length, 4 * (LEVEL_HEIGHTS.length - 1) * 6);
    for (let v = 0; v < primitive.vertexCount; v++) {
      const y = primitive.positions[3 * v + 1];
      const level = LEVEL_HEIGHTS.findIndex((h) => Math.abs(h - y) < 1e-6);
      const raw = figureInfluences(level, primitive.positions[3 * v], options);
      const rawSum = raw.reduce((s, [, w]) => s + w, 0);
      const expected = new Map<number, number>();
      for (const [joint, w] of raw) expected.set(joint, (expected.get(joint) ?? 0) + w / rawSum);
      const actual = new Map<number, number>();
      let sum = 0;
      for (let k = 0; k < primitive.influences; k++) {
        const w = primitive.weights![primitive.influences * v + k];
        sum += w;
        if (w > 0) actual.set(primitive.joints![primitive.influences * v + k], (actual.get(primitive.joints![primitive.influences * v + k]) ?? 0) + w);
      }
      assert.ok(Math.abs(sum - 1) < 1e-6, `vertex ${v} weights sum to ${sum}`);
      assert.deepEqual([...actual.keys()].sort(), [...expected.keys()].sort(), `vertex ${v} joints`);
      for (const [joint, w] of expected) assert.ok(Math.abs(actual.get(joint)! - w) < 1e-6, `vertex ${v} joint ${joint}`);
    }
    assert.equal(body.targetCount, 1);
    assert.deepEqual(body.weights, [0]);
    assert.equal(model.drawables.length, 2);
    const skinned = model.drawables.filter((d) => d.skin >= 0);
    assert.equal(skinned.length, 1);
    assert.equal(model.nodes[skinned[0].node].name, 'Body');
    const material = model.materials[primitive.material];
    assert.equal(material.name, 'Skin');
    assert.ok(material.hasBaseColorTexture && material.hasNormalTexture);
  }
});

test('reads both clips with durations, paths and interpolations', () => {
  const model = readAnimatedModel(createRiggedFigure().document);
  assert.deepEqual(model.clips.map((c) => c.id), ['Walk', 'Idle']);
  const [walk, idle] = model.clips;
  assert.equal(walk.durationS, 1);
  assert.equal(idle.durationS, 2);
  const describe = (c: (typeof walk.channels)[number]): string => `${model.nodes[c.node].name}.${c.path}:${c.sampler.interpolation}`;
  assert.deepEqual(walk.channels.map(describe), ['Hips.translation:LINEAR', 'LeftLeg.rotation:LINEAR', 'RightLeg.rotation:LINEAR', 'Spine.rotation:CUBICSPLINE']);
  assert.deepEqual(idle.channels.map(describe), ['Hips.translation:LINEAR', 'Head.rotation:STEP', 'Body.weights:LINEAR']);
  assert.equal(idle.channels[2].sampler.components, 1);
});

test('a GLB round trip through gltf-transform IO reads the same model', async () => {
  const { document } = createRiggedFigure({ eightInfluences: true });
  const io = new NodeIO();
  const glb = await io.writeBinary(document);
  const reread = readAnimatedModel(await io.readBinary(glb));
  const original = readAnimatedModel(document);
  assert.deepEqual(reread.nodes.map((n) => n.name), original.nodes.map((n) => n.name));
  const body = (m: typeof original): (typeof original.meshes)[number]['primitives'][number] => m.meshes.find((mesh) => mesh.name === 'Body')!.primitives[0];
  const a = body(original);
  const b = body(reread);
  assertClose(b.positions, a.positions, 0, 'positions');
  assertClose(b.weights!, a.weights!, 0, 'weights');
  assert.deepEqual([...b.joints!], [...a.joints!]);
  assertClose(reread.skins[0].inverseBindMatrices, original.skins[0].inverseBindMatrices, 0, 'inverse bind');
  assertClose(reread.clips[0].channels[3].sampler.output, original.clips[0].channels[3].sampler.output, 0, 'cubic output');
});

test('only mesh nodes of the default scene are drawn', () => {
  const { document } = createRiggedFigure();
  const ghostMesh = document.getRoot().listMeshes().find((m) => m.getName() === 'Badge')!;
  document.createNode('Ghost').setMesh(ghostMesh); // in the document, in no scene
  const model = readAnimatedModel(document);
  assert.ok(model.nodes.some((n) => n.name === 'Ghost'));
  assert.deepEqual(model.drawables.map((d) => model.nodes[d.node].name).sort(), ['Badge', 'Body']);
});

/** The figure body's vertex of face `f`, level `l`, side a (0) or b (1), as the fixture lays them out. */
const bodyVertex = (f: number, l: number, side: 0 | 1): number => f * LEVEL_HEIGHTS.length * 2 + 2 * l + side;
const FACE_COUNT = 4;
const RESTART = 0xffff;

/** Each triangle rotated to start at its smallest index (winding kept), sorted: the set of triangles drawn. */
function triangleSet(indices: ArrayLike<number>): string[] {
  const out: string[] = [];
  for (let t = 0; t < indices.length; t += 3) {
    const tri = [indices[t], indices[t + 1], indices[t + 2]];
    const first = tri.indexOf(Math.min(...tri));
    out.push([0, 1, 2].map((k) => tri[(first + k) % 3]).join(','));
  }
  return out.sort();
}

/** The rigged figure with its body primitive's indices replaced (mode and index list). */
function figureWithBody(mode: ReturnType<Primitive['getMode']>, indices: number[], restart = true): ReturnType<typeof createRiggedFigure>['document'] {
  const { document } = createRiggedFigure();
  if (restart) document.createExtension(KHRMeshPrimitiveRestart);
  const body = document.getRoot().listMeshes().find((m) => m.getName() === 'Body')!.listPrimitives()[0];
  body.setMode(mode).getIndices()!.setArray(new Uint16Array(indices));
  return document;
}

test('TRIANGLE_STRIP and TRIANGLE_FAN primitives with primitive restart read as the triangles of their triangle lists, and reach the raster meshes so', () => {
  const bodyOf = (model: ReturnType<typeof readAnimatedModel>) => model.meshes[model.nodes.find((n) => n.name === 'Body')!.mesh].primitives[0];
  const levels = LEVEL_HEIGHTS.length;
  // One strip up each face, zig-zagging a, b, a, b...: glTF 3.7.2.1 gives band l the triangles
  // (a_l, b_l, a_l+1) and (b_l, b_l+1, a_l+1), written out here as the list equivalent.
  const strip: number[] = [];
  const stripList: number[] = [];
  for (let f = 0; f < FACE_COUNT; f++) {
    if (f > 0) strip.push(RESTART);
    for (let l = 0; l < levels; l++) strip.push(bodyVertex(f, l, 0), bodyVertex(f, l, 1));
    for (let l = 0; l + 1 < levels; l++) stripList.push(bodyVertex(f, l, 0), bodyVertex(f, l, 1), bodyVertex(f, l + 1, 0), bodyVertex(f, l, 1), bodyVertex(f, l + 1, 1), bodyVertex(f, l + 1, 0));
  }
  const fromStrip = readAnimatedModel(figureWithBody(Primitive.Mode.TRIANGLE_STRIP, strip));
  const fromList = readAnimatedModel(figureWithBody(Primitive.Mode.TRIANGLES, stripList, false));
  assert.deepEqual(triangleSet(bodyOf(fromStrip).indices), triangleSet(stripList));
  assert.deepEqual(triangleSet(bodyOf(fromList).indices), triangleSet(stripList));
  // Every strip triangle faces out of the body, as the face's NORMAL does (counter-clockwise kept).
  const body = bodyOf(fromStrip);
  const p = (i: number): number[] => [0, 1, 2].map((k) => body.positions[3 * i + k]);
  for (let t = 0; t < body.indices.length; t += 3) {
    const [a, b, c] = [p(body.indices[t]), p(body.indices[t + 1]), p(body.indices[t + 2])];
    const e1 = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    const e2 = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    const n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]];
    const normal = [0, 1, 2].map((k) => body.normals![3 * body.indices[t] + k]);
    assert.ok(n[0] * normal[0] + n[1] * normal[1] + n[2] * normal[2] > 0, `strip triangle ${t / 3} faces outward`);
  }

  // One fan per quad, around a_l: b_l, b_l+1, a_l+1 gives the fixture's own triangle list.
  const fan: number[] = [];
  for (let f = 0; f < FACE_COUNT; f++) {
    for (let l = 0; l + 1 < levels; l++) fan.push(bodyVertex(f, l, 0), bodyVertex(f, l, 1), bodyVertex(f, l + 1, 1), bodyVertex(f, l + 1, 0), RESTART);
  }
  const original = readAnimatedModel(createRiggedFigure().document);
  const fromFan = readAnimatedModel(figureWithBody(Primitive.Mode.TRIANGLE_FAN, fan));
  assert.deepEqual(triangleSet(bodyOf(fromFan).indices), triangleSet(bodyOf(original).indices));

  // What the raster renderer uploads: the strip figure's skinned body mesh carries the list's triangles.
  const parts = modelRasterParts(fromStrip, (m) => (m >= 0 ? m : undefined));
  const drawn = parts.parts.find((part) => part.kind === 'skinned' && fromStrip.drawables[part.drawable].node === fromStrip.nodes.findIndex((n) => n.name === 'Body'))!;
  assert.deepEqual(triangleSet(parts.skinnedMeshes[drawn.index].indices!), triangleSet(stripList));

  // Without KHR_mesh_primitive_restart in use, 0xffff is an index out of range, refused by name.
  expectRendererError(() => readAnimatedModel(figureWithBody(Primitive.Mode.TRIANGLE_STRIP, strip, false), { field: 'modelAsset' }), 'INVALID_MODEL', `modelAsset.meshes[${fromStrip.nodes.find((n) => n.name === 'Body')!.mesh}].primitives[0].indices`, /index 12 is 65535/);
});
