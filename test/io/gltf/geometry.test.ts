import { test } from 'node:test';
import assert from 'node:assert/strict';
import { Document, Primitive } from '@gltf-transform/core';
import { EXTMeshoptCompression, KHRAccessorFloat16, KHRAccessorFloat64, KHRDracoMeshCompression, KHRMeshPrimitiveRestart, KHRMeshQuantization } from '@gltf-transform/extensions';
import { MeshoptEncoder } from 'meshoptimizer';
import { loadGltfScene } from '../../../src/io/index.ts';
import { toTriangleList } from '../../../src/io/gltf/primitive/topology.ts';
import { accessor, assertClose, rejectsWith, toGlb } from './helpers.ts';

/** z component of the counter-clockwise normal of each triangle. */
function triangleNormalZ(positions: ArrayLike<number>, indices: ArrayLike<number>): number[] {
  const out: number[] = [];
  for (let t = 0; t < indices.length; t += 3) {
    const [a, b, c] = [indices[t], indices[t + 1], indices[t + 2]].map((i) => [positions[i * 3], positions[i * 3 + 1], positions[i * 3 + 2]]);
    out.push((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
  }
  return out;
}

test('strips and fans become triangle lists with counter-clockwise winding kept (glTF 3.7.2.1)', () => {
  // Strip: a zig-zag 0-1-2-3-4-5 along x; triangles (0,1,2), (1,3,2), (2,3,4), (3,5,4).
  assert.deepEqual([...toTriangleList(5, Uint32Array.from([0, 1, 2, 3, 4, 5]))], [0, 1, 2, 1, 3, 2, 2, 3, 4, 3, 5, 4]);
  // Fan around vertex 0: (1,2,0), (2,3,0), (3,4,0).
  assert.deepEqual([...toTriangleList(6, Uint32Array.from([0, 1, 2, 3, 4]))], [1, 2, 0, 2, 3, 0, 3, 4, 0]);
  // Degenerate stitching triangles are dropped (parity, and so winding, continues through them);
  // primitive restart splits strips, each restarting at even parity.
  assert.deepEqual([...toTriangleList(5, Uint32Array.from([0, 1, 2, 2, 3, 4, 5]))], [0, 1, 2, 2, 4, 3, 3, 4, 5]);
  assert.deepEqual([...toTriangleList(5, Uint32Array.from([0, 1, 2, 0xffff, 3, 4, 5]), 0xffff)], [0, 1, 2, 3, 4, 5]);
  // An incomplete last triangle of a list is dropped.
  assert.deepEqual([...toTriangleList(4, Uint32Array.from([0, 1, 2, 3]))], [0, 1, 2]);
});

test('strip, fan, non-indexed and point primitives in a file', async () => {
  const doc = new Document();
  const buffer = doc.createBuffer();
  // Strip over a 3x2 grid of vertices in the xy plane, first triangle counter-clockwise: every
  // triangle must then face +z.
  const stripPositions = new Float32Array([0, 1, 0, 0, 0, 0, 1, 1, 0, 1, 0, 0, 2, 1, 0, 2, 0, 0]);
  const strip = doc.createPrimitive().setMode(Primitive.Mode.TRIANGLE_STRIP).setAttribute('POSITION', accessor(doc, buffer, 'VEC3', stripPositions));
  // Fan: a centre and a ring counter-clockwise around it, non-indexed.
  const ring = Array.from({ length: 7 }, (_, i) => [Math.cos((i * Math.PI) / 3), Math.sin((i * Math.PI) / 3), 0]).flat();
  const fan = doc.createPrimitive().setMode(Primitive.Mode.TRIANGLE_FAN).setAttribute('POSITION', accessor(doc, buffer, 'VEC3', new Float32Array([0, 0, 0, ...ring])));
  const points = doc.createPrimitive().setMode(Primitive.Mode.POINTS).setAttribute('POSITION', accessor(doc, buffer, 'VEC3', new Float32Array([0, 0, 0, 1, 1, 1])));
  const lines = doc.createPrimitive().setMode(Primitive.Mode.LINES).setAttribute('POSITION', accessor(doc, buffer, 'VEC3', new Float32Array([0, 0, 0, 1, 1, 1])));
  const list = doc.createPrimitive().setAttribute('POSITION', accessor(doc, buffer, 'VEC3', new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0])));
  const mesh = doc.createMesh('mixed').addPrimitive(strip).addPrimitive(fan).addPrimitive(points).addPrimitive(lines).addPrimitive(list);
  doc.createScene().addChild(doc.createNode('n').setMesh(mesh));
  const scene = await loadGltfScene(await toGlb(doc));

  assert.equal(scene.meshes.length, 3);
  assert.equal(scene.instances.length, 3);
  const [s, f, l] = scene.meshes;
  assert.equal(s.indices!.length, 12);
  assert.ok(triangleNormalZ(s.positions, s.indices!).every((z) => z > 0), 'strip winding');
  assert.equal(f.indices!.length, 18);
  assert.ok(triangleNormalZ(f.positions, f.indices!).every((z) => z > 0), 'fan winding');
  assert.deepEqual(Array.from(l.indices!), [0, 1, 2], 'non-indexed list: sequential indices');
  assert.ok(!scene.warnings.some((w) => w.startsWith('/meshes/0/primitives/4')), 'whole triangles: no warning');
  assert.equal(l.normals, undefined, 'no NORMAL: normals omitted (flat shading)');
  assert.ok(scene.warnings.some((w) => w.startsWith('/meshes/0/primitives/2: skipped') && /POINTS/.test(w)), scene.warnings.join('\n'));
  assert.ok(scene.warnings.some((w) => w.startsWith('/meshes/0/primitives/3: skipped') && /LINES/.test(w)));
});

test('a TRIANGLES primitive whose index count is not a multiple of 3 keeps its whole triangles, with a warning', async () => {
  const doc = new Document();
  const buffer = doc.createBuffer();
  const primitive = doc.createPrimitive()
    .setAttribute('POSITION', accessor(doc, buffer, 'VEC3', new Float32Array([0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0])))
    .setIndices(accessor(doc, buffer, 'SCALAR', new Uint16Array([0, 1, 2, 0, 2, 3, 0, 1])));
  doc.createScene().addChild(doc.createNode('n').setMesh(doc.createMesh().addPrimitive(primitive)));
  const scene = await loadGltfScene(await toGlb(doc));
  assert.deepEqual(Array.from(scene.meshes[0]!.indices!), [0, 1, 2, 0, 2, 3]);
  assert.ok(scene.warnings.includes('/meshes/0/primitives/0: 8 indices are not whole triangles; the last 2 ignored'), scene.warnings.join('\n'));
});

test('KHR_mesh_quantization: integer positions, normalised normals, uvs and colours are dequantised', async () => {
  const doc = new Document();
  doc.createExtension(KHRMeshQuantization).setRequired(true);
  const buffer = doc.createBuffer();
  const positions = new Int16Array([0, 0, 0, 1000, 0, 0, 0, 1000, 0]);
  const normals = new Int8Array([0, 0, 127, 0, 0, 127, 0, -128, 0]);
  const uvs = new Uint16Array([0, 0, 65535, 0, 0, 32768]);
  const colors = new Uint8Array([255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 51, 255]);
  const primitive = doc
    .createPrimitive()
    .setAttribute('POSITION', accessor(doc, buffer, 'VEC3', positions))
    .setAttribute('NORMAL', accessor(doc, buffer, 'VEC3', normals, true))
    .setAttribute('TEXCOORD_0', accessor(doc, buffer, 'VEC2', uvs, true))
    .setAttribute('COLOR_0', accessor(doc, buffer, 'VEC4', colors, true));
  // The dequantisation scale lives in the node transform, as quantisers write it.
  doc.createScene().addChild(doc.createNode('q').setMesh(doc.createMesh().addPrimitive(primitive)).setScale([0.001, 0.001, 0.001]));
  const scene = await loadGltfScene(await toGlb(doc));
  const m = scene.meshes[0];
  assertClose(m.positions, [0, 0, 0, 1000, 0, 0, 0, 1000, 0], 0, 'positions');
  assertClose(m.normals!, [0, 0, 1, 0, 0, 1, 0, -1, 0], 1e-7, 'normals (max(c / 127, -1))');
  assertClose(m.uvs!, [0, 0, 1, 0, 0, 32768 / 65535], 1e-7, 'uvs');
  assertClose(m.colors!, [1, 0, 0, 1, 0, 1, 0, 128 / 255, 0, 0, 0.2, 1], 1e-7, 'colors');
  assertClose(scene.instances[0].transform!, [0.001, 0, 0, 0, 0, 0.001, 0, 0, 0, 0, 0.001, 0, 0, 0, 0, 1], 1e-12, 'scale');
});

test('morph targets apply the node weights', async () => {
  const doc = new Document();
  const buffer = doc.createBuffer();
  const primitive = doc.createPrimitive().setAttribute('POSITION', accessor(doc, buffer, 'VEC3', new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0])));
  primitive.addTarget(doc.createPrimitiveTarget().setAttribute('POSITION', accessor(doc, buffer, 'VEC3', new Float32Array([0, 0, 2, 0, 0, 2, 0, 0, 2]))));
  const mesh = doc.createMesh().addPrimitive(primitive).setWeights([0]);
  doc.createScene().addChild(doc.createNode('rest').setMesh(mesh)).addChild(doc.createNode('half').setMesh(mesh).setWeights([0.5]));
  const scene = await loadGltfScene(await toGlb(doc));
  assert.equal(scene.meshes.length, 2, 'different weights, different geometry');
  assertClose(scene.meshes[scene.instances[0].mesh].positions, [0, 0, 0, 1, 0, 0, 0, 1, 0], 0, 'rest');
  assertClose(scene.meshes[scene.instances[1].mesh].positions, [0, 0, 1, 1, 0, 1, 0, 1, 1], 0, 'half');
});

/** A bumpy 8x8 grid surface with normals and uvs. */
function gridPrimitive(doc: Document): { primitive: Primitive; positions: Float32Array; indices: Uint32Array } {
  const n = 8;
  const positions: number[] = [];
  const normals: number[] = [];
  const uvs: number[] = [];
  for (let j = 0; j <= n; j++) {
    for (let i = 0; i <= n; i++) {
      positions.push(i / n, j / n, 0.1 * Math.sin(i) * Math.cos(j));
      normals.push(0, 0, 1);
      uvs.push(i / n, 1 - j / n);
    }
  }
  const indices: number[] = [];
  for (let j = 0; j < n; j++) {
    for (let i = 0; i < n; i++) {
      const a = j * (n + 1) + i;
      indices.push(a, a + 1, a + n + 2, a, a + n + 2, a + n + 1);
    }
  }
  const buffer = doc.getRoot().listBuffers()[0] ?? doc.createBuffer();
  const p = new Float32Array(positions);
  const primitive = doc
    .createPrimitive()
    .setAttribute('POSITION', accessor(doc, buffer, 'VEC3', p))
    .setAttribute('NORMAL', accessor(doc, buffer, 'VEC3', new Float32Array(normals)))
    .setAttribute('TEXCOORD_0', accessor(doc, buffer, 'VEC2', new Float32Array(uvs)))
    .setIndices(accessor(doc, buffer, 'SCALAR', new Uint32Array(indices)));
  return { primitive, positions: p, indices: new Uint32Array(indices) };
}

/** Sorted triangle centroids: compares geometry independent of vertex order. */
function centroids(positions: ArrayLike<number>, indices: ArrayLike<number>): number[][] {
  const out: number[][] = [];
  for (let t = 0; t < indices.length; t += 3) {
    out.push([0, 1, 2].map((k) => (positions[indices[t] * 3 + k] + positions[indices[t + 1] * 3 + k] + positions[indices[t + 2] * 3 + k]) / 3));
  }
  return out.sort((a, b) => a[0] - b[0] || a[1] - b[1] || a[2] - b[2]);
}

test('KHR_draco_mesh_compression: a Draco-encoded mesh decodes to the same triangles', async () => {
  const doc = new Document();
  const { primitive, positions, indices } = gridPrimitive(doc);
  doc.createScene().addChild(doc.createNode('d').setMesh(doc.createMesh('draco').addPrimitive(primitive)));
  doc.createExtension(KHRDracoMeshCompression).setRequired(true).setEncoderOptions({ quantizationBits: { POSITION: 16, NORMAL: 10, TEX_COORD: 12 } });
  // draco3dgltf ships no type declarations: import it through a variable specifier.
  const specifier = 'draco3dgltf';
  const draco3d = ((await import(specifier)) as { default: { createEncoderModule(): Promise<unknown> } }).default;
  const glb = await toGlb(doc, { 'draco3d.encoder': await draco3d.createEncoderModule() });
  assert.ok(new TextDecoder().decode(glb).includes('KHR_draco_mesh_compression'));
  const scene = await loadGltfScene(glb);
  assert.deepEqual(scene.extensionsUsed, ['KHR_draco_mesh_compression']);
  const m = scene.meshes[0];
  assert.equal(m.indices!.length, indices.length);
  // 16-bit quantisation of a ~1.1 unit range: error below 2e-5 per coordinate.
  const got = centroids(m.positions, m.indices!);
  const want = centroids(positions, indices);
  got.forEach((c, i) => assertClose(c, want[i], 2e-5, `centroid ${i}`));
  assert.equal(m.uvs!.length / 2, m.positions.length / 3);
});

test('EXT_meshopt_compression: a meshopt-encoded mesh decodes to the same data', async () => {
  await MeshoptEncoder.ready;
  const doc = new Document();
  const { primitive, positions, indices } = gridPrimitive(doc);
  doc.createScene().addChild(doc.createNode('m').setMesh(doc.createMesh('meshopt').addPrimitive(primitive)));
  doc.createExtension(EXTMeshoptCompression).setRequired(true).setEncoderOptions({ method: EXTMeshoptCompression.EncoderMethod.FILTER });
  const glb = await toGlb(doc, { 'meshopt.encoder': MeshoptEncoder });
  assert.ok(new TextDecoder().decode(glb).includes('EXT_meshopt_compression'));
  const scene = await loadGltfScene(glb);
  assert.ok(scene.extensionsUsed.includes('EXT_meshopt_compression'));
  const m = scene.meshes[0];
  // Positions and indices are losslessly compressed with the FILTER method.
  assertClose(m.positions, positions, 0, 'positions');
  // The index codec keeps every triangle and its winding but may rotate its corners.
  const canonical = (ix: ArrayLike<number>): string[] => {
    const out: string[] = [];
    for (let t = 0; t < ix.length; t += 3) {
      const tri = [ix[t], ix[t + 1], ix[t + 2]];
      const k = tri.indexOf(Math.min(...tri));
      out.push([tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]].join(','));
    }
    return out.sort();
  };
  assert.deepEqual(canonical(m.indices!), canonical(indices));
  // Normals go through an 8-bit octahedral filter.
  for (let i = 0; i < m.normals!.length; i += 3) assertClose(Array.from(m.normals!).slice(i, i + 3), [0, 0, 1], 0.02, `normal ${i / 3}`);
});

/** The GLB's BIN chunk payload, overwritten from `from` on with a pseudo-random byte pattern. */
function scrambleBin(glb: Uint8Array, from = 0): Uint8Array {
  const out = glb.slice();
  const view = new DataView(out.buffer);
  const binStart = 20 + view.getUint32(12, true) + 8;
  for (let i = binStart + from; i < out.length; i++) out[i] = (i * 7919 + 13) & 255;
  return out;
}

/** The GLB with its JSON chunk replaced by `edit(json)` (same length budget: re-laid out). */
// eslint-disable-next-line @typescript-eslint/no-explicit-any -- free-form JSON surgery
function editGlbJson(glb: Uint8Array, edit: (json: any) => void): Uint8Array {
  const view = new DataView(glb.buffer, glb.byteOffset, glb.byteLength);
  const jsonLength = view.getUint32(12, true);
  const json = JSON.parse(new TextDecoder().decode(glb.subarray(20, 20 + jsonLength)));
  edit(json);
  const text = new TextEncoder().encode(JSON.stringify(json));
  const padded = new Uint8Array(Math.ceil(text.length / 4) * 4).fill(0x20);
  padded.set(text);
  const rest = glb.subarray(20 + jsonLength);
  const out = new Uint8Array(20 + padded.length + rest.length);
  out.set(glb.subarray(0, 12));
  const o = new DataView(out.buffer);
  o.setUint32(8, out.length, true);
  o.setUint32(12, padded.length, true);
  o.setUint32(16, 0x4e4f534a, true);
  out.set(padded, 20);
  out.set(rest, 20 + padded.length);
  return out;
}

test('corrupt compressed geometry names the Draco primitive or meshopt buffer view', async () => {
  const specifier = 'draco3dgltf';
  const draco3d = ((await import(specifier)) as { default: { createEncoderModule(): Promise<unknown> } }).default;
  const dracoDoc = new Document();
  dracoDoc.createScene().addChild(dracoDoc.createNode('d').setMesh(dracoDoc.createMesh().addPrimitive(gridPrimitive(dracoDoc).primitive)));
  dracoDoc.createExtension(KHRDracoMeshCompression).setRequired(true);
  const dracoGlb = await toGlb(dracoDoc, { 'draco3d.encoder': await draco3d.createEncoderModule() });
  const at = '/meshes/0/primitives/0/extensions/KHR_draco_mesh_compression';
  await rejectsWith(loadGltfScene(scrambleBin(dracoGlb)), 'INVALID_GLTF', at, /Draco data/);
  const wrongId = editGlbJson(dracoGlb, (json) => (json.meshes[0].primitives[0].extensions.KHR_draco_mesh_compression.attributes.NORMAL = 17));
  // The reader decodes an unknown attribute id to nothing; the element count check names it.
  await rejectsWith(loadGltfScene(wrongId), 'INVALID_GLTF', '/meshes/0/primitives/0/attributes/NORMAL', /0 elements, the primitive's POSITION has 81/);

  await MeshoptEncoder.ready;
  const meshoptDoc = new Document();
  meshoptDoc.createScene().addChild(meshoptDoc.createNode('m').setMesh(meshoptDoc.createMesh().addPrimitive(gridPrimitive(meshoptDoc).primitive)));
  meshoptDoc.createExtension(EXTMeshoptCompression).setRequired(true);
  const meshoptGlb = await toGlb(meshoptDoc, { 'meshopt.encoder': MeshoptEncoder });
  await rejectsWith(loadGltfScene(scrambleBin(meshoptGlb)), 'INVALID_GLTF', '/bufferViews/0/extensions/EXT_meshopt_compression', /does not decode/);
  const badMode = editGlbJson(meshoptGlb, (json) => (json.bufferViews[0].extensions.EXT_meshopt_compression.mode = 'POINTS'));
  await rejectsWith(loadGltfScene(badMode), 'INVALID_GLTF', '/bufferViews/0/extensions/EXT_meshopt_compression/mode', /"POINTS"/);
  const badFilter = editGlbJson(meshoptGlb, (json) => (json.bufferViews[0].extensions.EXT_meshopt_compression.filter = 'ZIGZAG'));
  await rejectsWith(loadGltfScene(badFilter), 'INVALID_GLTF', '/bufferViews/0/extensions/EXT_meshopt_compression/filter', /"ZIGZAG"/);
});

test('KHR_accessor_float64 and _float16 positions, and KHR_mesh_primitive_restart strips, read as float32 triangle lists', async () => {
  const doc = new Document();
  doc.createExtension(KHRAccessorFloat64).setRequired(true);
  doc.createExtension(KHRAccessorFloat16).setRequired(true);
  doc.createExtension(KHRMeshPrimitiveRestart);
  const buffer = doc.createBuffer();
  // Two strips of two triangles each in one index buffer, split by the restart value 0xffff.
  const strips = [0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 3, 0, 0, 4, 0, 0, 3, 1, 0, 4, 1, 0];
  const wide = doc.createPrimitive()
    .setMode(Primitive.Mode.TRIANGLE_STRIP)
    .setAttribute('POSITION', doc.createAccessor().setType('VEC3').setArray(new Float64Array(strips)).setBuffer(buffer))
    .setIndices(accessor(doc, buffer, 'SCALAR', new Uint16Array([0, 1, 2, 3, 0xffff, 4, 5, 6, 7])));
  const half = doc.createPrimitive()
    .setAttribute('POSITION', doc.createAccessor().setType('VEC3').setArray(new Float16Array([0, 0, 0, 0.5, 0, 0, 0, 0.25, 0]) as never).setBuffer(buffer));
  doc.createScene().addChild(doc.createNode('n').setMesh(doc.createMesh().addPrimitive(wide).addPrimitive(half)));
  const scene = await loadGltfScene(await toGlb(doc));
  assert.deepEqual(scene.extensionsUsed.toSorted(), ['KHR_accessor_float16', 'KHR_accessor_float64', 'KHR_mesh_primitive_restart']);
  const [a, b] = scene.meshes;
  assert.ok(a!.positions instanceof Float32Array && b!.positions instanceof Float32Array);
  assertClose(a!.positions, strips, 0, 'float64 positions');
  assert.deepEqual(Array.from(a!.indices!), [0, 1, 2, 1, 3, 2, 4, 5, 6, 5, 7, 6], 'each strip starts afresh after the restart value');
  assertClose(b!.positions, [0, 0, 0, 0.5, 0, 0, 0, 0.25, 0], 0, 'float16 positions');
});
