// One test per loader error: the asset is corrupted on purpose and the typed error must carry code
// INVALID_GLTF and the exact JSON pointer (or glb: path) of the fault.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtemp, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { Document, type GLTF } from '@gltf-transform/core';
import { KHRTextureBasisu } from '@gltf-transform/extensions';
import { createDefaultContainer, write as writeKtx2 } from 'ktx-parse';
import { loadGltfScene } from '../../../src/io/index.ts';
import { accessor, createIO, quadMesh, rejectsWith, toGlb } from './helpers.ts';

/** A GLB with an arbitrary JSON and BIN payload, laid out per glTF 2.0 section 4.4. */
function makeGlb(json: unknown, bin?: Uint8Array): Uint8Array {
  const pad = (bytes: Uint8Array, fill: number): Uint8Array => {
    const out = new Uint8Array(Math.ceil(bytes.length / 4) * 4).fill(fill);
    out.set(bytes);
    return out;
  };
  const jsonChunk = pad(new TextEncoder().encode(JSON.stringify(json)), 0x20);
  const binChunk = bin === undefined ? undefined : pad(bin, 0);
  const length = 12 + 8 + jsonChunk.length + (binChunk ? 8 + binChunk.length : 0);
  const out = new Uint8Array(length);
  const view = new DataView(out.buffer);
  view.setUint32(0, 0x46546c67, true);
  view.setUint32(4, 2, true);
  view.setUint32(8, length, true);
  view.setUint32(12, jsonChunk.length, true);
  view.setUint32(16, 0x4e4f534a, true);
  out.set(jsonChunk, 20);
  if (binChunk) {
    view.setUint32(20 + jsonChunk.length, binChunk.length, true);
    view.setUint32(24 + jsonChunk.length, 0x004e4942, true);
    out.set(binChunk, 28 + jsonChunk.length);
  }
  return out;
}

/** A valid one-quad asset as { json, bin } to corrupt. */
async function quadAsset(): Promise<{ json: GLTF.IGLTF; bin: Uint8Array }> {
  const doc = new Document();
  doc.createScene().addChild(doc.createNode('n').setMesh(quadMesh(doc, doc.createBuffer())));
  const { json, resources } = await createIO().writeJSON(doc, { format: 1 as never });
  const bin = Object.values(resources)[0];
  delete json.buffers![0].uri;
  return { json, bin };
}

const bad = (bytes: Uint8Array, field: string, message?: RegExp): Promise<void> => rejectsWith(loadGltfScene(bytes), 'INVALID_GLTF', field, message);

test('the unmodified test asset loads', async () => {
  const { json, bin } = await quadAsset();
  const scene = await loadGltfScene(makeGlb(json, bin));
  assert.equal(scene.meshes.length, 1);
});

test('GLB header: magic, version, length', async () => {
  const { json, bin } = await quadAsset();
  const glb = makeGlb(json, bin);
  const corrupt = (offset: number, value: number): Uint8Array => {
    const copy = glb.slice();
    new DataView(copy.buffer).setUint32(offset, value, true);
    return copy;
  };
  // Wrong magic: not JSON text either, so the magic is what is reported.
  await bad(corrupt(0, 0x46546c68), 'glb:/header/magic', /0x46546c68/);
  await bad(corrupt(4, 1), 'glb:/header/version', /version 2, got 1/);
  await bad(corrupt(8, glb.length + 100), 'glb:/header/length', /truncated/);
  await bad(glb.subarray(0, glb.length - 8), 'glb:/header/length');
  await bad(glb.subarray(0, 10), 'glb:/header', /12 bytes/);
});

test('GLB chunks: JSON chunk type and chunk lengths', async () => {
  const { json, bin } = await quadAsset();
  const glb = makeGlb(json, bin);
  const view = (bytes: Uint8Array): DataView => new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const notJson = glb.slice();
  view(notJson).setUint32(16, 0x004e4942, true);
  await bad(notJson, 'glb:/chunks/0/chunkType');
  const longJson = glb.slice();
  view(longJson).setUint32(12, glb.length, true);
  await bad(longJson, 'glb:/chunks/0/chunkLength', /run past the end/);
  const jsonLength = view(glb).getUint32(12, true);
  const longBin = glb.slice();
  view(longBin).setUint32(20 + jsonLength, bin.length + 64, true);
  await bad(longBin, 'glb:/chunks/1/chunkLength');
});

test('truncated buffer: the BIN chunk is shorter than the buffer\'s byteLength', async () => {
  const { json, bin } = await quadAsset();
  await bad(makeGlb(json, bin.subarray(0, bin.length - 16)), '/buffers/0/byteLength', /truncated/);
});

test('buffer view beyond its buffer', async () => {
  const { json, bin } = await quadAsset();
  json.bufferViews![1].byteOffset = bin.length;
  await bad(makeGlb(json, bin), '/bufferViews/1', /past the end of buffer 0/);
});

test('accessor beyond its buffer view (byteOffset + stride * (count - 1) + element size)', async () => {
  const { json, bin } = await quadAsset();
  // Accessor 3 holds the quad's 6 uint16 indices (12 bytes): 4 bytes further in, they need 16.
  json.accessors![3].byteOffset = 4;
  await bad(makeGlb(json, bin), '/accessors/3', /need 16 bytes/);
});

test('indices beyond the vertex count', async () => {
  const doc = new Document();
  const buffer = doc.createBuffer();
  const mesh = quadMesh(doc, buffer);
  mesh.listPrimitives()[0].setIndices(accessor(doc, buffer, 'SCALAR', new Uint16Array([0, 1, 2, 0, 2, 4])));
  doc.createScene().addChild(doc.createNode('n').setMesh(mesh));
  await bad(await toGlb(doc), '/meshes/0/primitives/0/indices', /index 5 is 4, the primitive has 4 vertices/);
});

test('non-finite positions, from bytes and from a Document', async () => {
  const doc = new Document();
  const buffer = doc.createBuffer();
  const good = quadMesh(doc, buffer, undefined, 'good');
  const broken = quadMesh(doc, buffer, undefined, 'broken');
  broken.listPrimitives()[0].getAttribute('POSITION')!.setArray(new Float32Array([0, 0, 0, 1, 0, 0, 1, NaN, 0, 0, 1, 0]));
  doc.createScene().addChild(doc.createNode('a').setMesh(good)).addChild(doc.createNode('b').setMesh(broken));
  await bad(await toGlb(doc), '/meshes/1/primitives/0/attributes/POSITION', /element 2/);
  await rejectsWith(loadGltfScene(doc), 'INVALID_GLTF', '/meshes/1/primitives/0/attributes/POSITION');
});

test('unsupported required extension', async () => {
  const doc = new Document();
  doc.createScene().addChild(doc.createNode('n').setMesh(quadMesh(doc, doc.createBuffer())));
  const { json, resources } = await createIO().writeJSON(doc);
  json.extensionsUsed = ['KHR_materials_unlit', 'MSFT_texture_dds'];
  json.extensionsRequired = ['KHR_materials_unlit', 'MSFT_texture_dds'];
  const buffer = json.buffers![0];
  buffer.uri = `data:application/octet-stream;base64,${Buffer.from(resources[buffer.uri!]).toString('base64')}`;
  await bad(new TextEncoder().encode(JSON.stringify(json)), '/extensionsRequired/1', /MSFT_texture_dds is not supported/);
});

test('an unsupported optional extension is drawn without, with one warning naming it; metadata-only ones pass silently', async () => {
  const doc = new Document();
  doc.createScene().addChild(doc.createNode('n').setMesh(quadMesh(doc, doc.createBuffer())));
  const { json, resources } = await createIO().writeJSON(doc);
  json.extensionsUsed = ['MSFT_lod', 'FB_ngon_encoding'];
  const buffer = json.buffers![0];
  buffer.uri = `data:application/octet-stream;base64,${Buffer.from(resources[buffer.uri!]).toString('base64')}`;
  const scene = await loadGltfScene(new TextEncoder().encode(JSON.stringify(json)));
  assert.deepEqual(scene.warnings, ['MSFT_lod: not supported; the asset is drawn without it']);
});

test('a KTX2 image that does not decode: truncated, or of a format the loader cannot read', async () => {
  const doc = new Document();
  doc.createExtension(KHRTextureBasisu).setRequired(true);
  const tex = doc.createTexture('gpu').setMimeType('image/ktx2').setImage(new Uint8Array([0xab, 0x4b, 0x54, 0x58, 0x20, 0x32, 0x30, 0xbb, 0x0d, 0x0a, 0x1a, 0x0a]));
  doc.createScene().addChild(doc.createNode('n').setMesh(quadMesh(doc, doc.createBuffer(), doc.createMaterial().setBaseColorTexture(tex))));
  await bad(await toGlb(doc), '/images/0', /KTX2 image does not decode: the KTX2 container does not parse/);
  // A well-formed container of a block-compressed format (BC7, vkFormat 145) is refused by name.
  const bc7 = createDefaultContainer();
  Object.assign(bc7, { vkFormat: 145, typeSize: 1, pixelWidth: 4, pixelHeight: 4, levels: [{ levelData: new Uint8Array(16), uncompressedByteLength: 16 }] });
  tex.setImage(writeKtx2(bc7));
  await bad(await toGlb(doc), '/images/0', /vkFormat 145 is not supported/);
});

test('undecodable image bytes, and an external image file that does not exist', async () => {
  const doc = new Document();
  const tex = doc.createTexture('broken').setMimeType('image/png').setImage(new Uint8Array([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 1, 2, 3]));
  doc.createScene().addChild(doc.createNode('n').setMesh(quadMesh(doc, doc.createBuffer(), doc.createMaterial().setBaseColorTexture(tex))));
  await bad(await toGlb(doc), '/images/0', /PNG image does not decode/);

  const dir = await mkdtemp(join(tmpdir(), 'gltf-missing-'));
  try {
    const { json, resources } = await createIO().writeJSON(doc);
    for (const [uri, bytes] of Object.entries(resources)) await writeFile(join(dir, uri), bytes);
    json.images![0].uri = 'textures/missing.png';
    await writeFile(join(dir, 'scene.gltf'), JSON.stringify(json));
    await rejectsWith(loadGltfScene(join(dir, 'scene.gltf')), 'INVALID_GLTF', '/images/0', /cannot read "textures\/missing.png"/);
  } finally {
    await rm(dir, { recursive: true, force: true });
  }
});

test('JSON faults: syntax, references, attribute types and a node cycle', async () => {
  const { json, bin } = await quadAsset();
  await bad(new TextEncoder().encode('{"asset": {"version": "2.0"'), '', /does not parse/);
  const copy = (): GLTF.IGLTF => structuredClone(json);
  let j = copy();
  j.nodes![0].mesh = 7;
  await bad(makeGlb(j, bin), '/nodes/0/mesh', /meshes index 7 is out of range/);
  j = copy();
  j.meshes![0].primitives[0].attributes.NORMAL = j.meshes![0].primitives[0].attributes.TEXCOORD_0;
  await bad(makeGlb(j, bin), '/meshes/0/primitives/0/attributes/NORMAL', /VEC3/);
  j = copy();
  j.nodes!.push({ children: [2] }, { children: [1] });
  await bad(makeGlb(j, bin), '/nodes/1', /cycle/);
  j = copy();
  j.nodes!.push({ children: [0] }, { children: [0] });
  await bad(makeGlb(j, bin), '/nodes/2/children/0', /already has parent 1/);
  j = copy();
  j.asset.version = '1.0';
  await bad(makeGlb(j, bin), '/asset/version');
});

/** `bin` with `extra` appended on a 4-byte boundary, and the offset it starts at. */
function appendBin(bin: Uint8Array, extra: Uint8Array): { bin: Uint8Array; offset: number } {
  const offset = Math.ceil(bin.length / 4) * 4;
  const out = new Uint8Array(offset + extra.length);
  out.set(bin);
  out.set(extra, offset);
  return { bin: out, offset };
}

test('GLB: a buffer without uri needs the BIN chunk; the JSON chunk must be UTF-8', async () => {
  const { json, bin } = await quadAsset();
  await bad(makeGlb(json), '/buffers/0', /no GLB BIN chunk/);
  const glb = makeGlb(json, bin);
  const notUtf8 = glb.slice();
  notUtf8[21] = 0xff; // inside the JSON chunk payload
  await bad(notUtf8, 'glb:/chunks/0', /UTF-8/);
});

test('external buffers: a missing .bin file and a truncated one', async () => {
  const doc = new Document();
  doc.createScene().addChild(doc.createNode('n').setMesh(quadMesh(doc, doc.createBuffer().setURI('geometry.bin'))));
  const { json, resources } = await createIO().writeJSON(doc);
  const dir = await mkdtemp(join(tmpdir(), 'gltf-buffers-'));
  try {
    await writeFile(join(dir, 'scene.gltf'), JSON.stringify(json));
    await rejectsWith(loadGltfScene(join(dir, 'scene.gltf')), 'INVALID_GLTF', '/buffers/0', /cannot read "geometry.bin"/);
    await writeFile(join(dir, 'geometry.bin'), resources['geometry.bin'].subarray(0, 20));
    await rejectsWith(loadGltfScene(join(dir, 'scene.gltf')), 'INVALID_GLTF', '/buffers/0/byteLength', /declared \d+ bytes, the data has 20 \(truncated\)/);
  } finally {
    await rm(dir, { recursive: true, force: true });
  }
});

test('missing images: no uri or bufferView, a texture source or a material texture index out of range', async () => {
  const { json, bin } = await quadAsset();
  const copy = (): GLTF.IGLTF => structuredClone(json);
  let j = copy();
  j.images = [{ mimeType: 'image/png' }];
  await bad(makeGlb(j, bin), '/images/0', /needs a uri or a bufferView/);
  j = copy();
  j.images = [];
  j.textures = [{ source: 0 }];
  await bad(makeGlb(j, bin), '/textures/0/source', /images index 0 is out of range \(the asset has 0 images\)/);
  j = copy();
  j.materials = [{ pbrMetallicRoughness: { baseColorTexture: { index: 3 } } }];
  j.meshes![0].primitives[0].material = 0;
  await bad(makeGlb(j, bin), '/materials/0/pbrMetallicRoughness/baseColorTexture/index', /textures index 3/);
  j = copy();
  j.materials = [{ extensions: { KHR_materials_clearcoat: { clearcoatNormalTexture: { index: 0 } } } }];
  await bad(makeGlb(j, bin), '/materials/0/extensions/KHR_materials_clearcoat/clearcoatNormalTexture/index');
  // A Document whose image has no data (never loaded) fails the same way, naming the image.
  const doc = new Document();
  const tex = doc.createTexture('lost').setURI('lost.png');
  doc.createScene().addChild(doc.createNode('n').setMesh(quadMesh(doc, doc.createBuffer(), doc.createMaterial().setBaseColorTexture(tex))));
  await rejectsWith(loadGltfScene(doc), 'INVALID_GLTF', '/images/0', /no data \(lost.png\)/);
});

test('any unsupported required extension is refused, before anything is read', async () => {
  const { json, bin } = await quadAsset();
  json.extensionsUsed = ['KHR_mesh_quantization', 'EXT_made_up'];
  json.extensionsRequired = ['KHR_mesh_quantization', 'EXT_made_up'];
  await bad(makeGlb(json, bin), '/extensionsRequired/1', /EXT_made_up is not supported/);
});

test('indices: a float accessor, and a sparse accessor whose indices leave its range or do not increase', async () => {
  const { json, bin } = await quadAsset();
  const j: GLTF.IGLTF = structuredClone(json);
  j.accessors![3].componentType = 5126;
  j.accessors![3].count = 3;
  await bad(makeGlb(j, bin), '/meshes/0/primitives/0/indices', /unsigned byte\/short\/int/);

  // Accessor 0 (POSITION, 4 vertices) gets a sparse substitution of 2 elements.
  const sparse = (indices: number[]): Uint8Array => {
    const extra = new Uint8Array(4 * 2 + 24);
    const view = new DataView(extra.buffer);
    indices.forEach((v, i) => view.setUint32(4 * i, v, true));
    for (let k = 0; k < 6; k++) view.setFloat32(8 + 4 * k, 0.5, true);
    const appended = appendBin(bin, extra);
    const out = structuredClone(json);
    out.buffers![0].byteLength = appended.bin.length;
    out.bufferViews!.push({ buffer: 0, byteOffset: appended.offset, byteLength: 8 }, { buffer: 0, byteOffset: appended.offset + 8, byteLength: 24 });
    const views = out.bufferViews!.length;
    out.accessors![0].sparse = { count: 2, indices: { bufferView: views - 2, componentType: 5125 }, values: { bufferView: views - 1 } };
    return makeGlb(out, appended.bin);
  };
  const ok = await loadGltfScene(sparse([1, 3]));
  assert.deepEqual(Array.from(ok.meshes[0].positions).slice(3, 6), [0.5, 0.5, 0.5], 'the substituted element');
  await bad(sparse([1, 4]), '/accessors/0/sparse/indices', /sparse index 1 is 4, the accessor has 4 elements/);
  await bad(sparse([3, 1]), '/accessors/0/sparse/indices', /strictly increase/);
});

test('a Document passed in is checked like a file: attribute sizes and counts, morph target counts', async () => {
  const sized = new Document();
  const b1 = sized.createBuffer();
  const m1 = quadMesh(sized, b1);
  m1.listPrimitives()[0].setAttribute('TEXCOORD_0', accessor(sized, b1, 'VEC3', new Float32Array(12)));
  sized.createScene().addChild(sized.createNode('n').setMesh(m1));
  await rejectsWith(loadGltfScene(sized), 'INVALID_GLTF', '/meshes/0/primitives/0/attributes/TEXCOORD_0', /2 components per element, the accessor has 3/);

  const counted = new Document();
  const b2 = counted.createBuffer();
  const m2 = quadMesh(counted, b2);
  m2.listPrimitives()[0].setAttribute('NORMAL', accessor(counted, b2, 'VEC3', new Float32Array([0, 0, 1, 0, 0, 1, 0, 0, 1])));
  counted.createScene().addChild(counted.createNode('n').setMesh(m2));
  await rejectsWith(loadGltfScene(counted), 'INVALID_GLTF', '/meshes/0/primitives/0/attributes/NORMAL', /3 elements, the primitive's POSITION has 4/);

  const morphed = new Document();
  const b3 = morphed.createBuffer();
  const m3 = quadMesh(morphed, b3).setWeights([1]);
  m3.listPrimitives()[0].addTarget(morphed.createPrimitiveTarget().setAttribute('NORMAL', accessor(morphed, b3, 'VEC3', new Float32Array(6))));
  morphed.createScene().addChild(morphed.createNode('n').setMesh(m3));
  await rejectsWith(loadGltfScene(morphed), 'INVALID_GLTF', '/meshes/0/primitives/0/targets/0/NORMAL', /2 elements, the primitive has 4 vertices/);
});
