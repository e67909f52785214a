// One test per loader error: the asset is corrupted on purpose and the typed error must carry code
// INVALID_GLTF and the exact JSON pointer (or glb: path) of the fault.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtemp, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { Document, type GLTF } from '@gltf-transform/core';
import { KHRTextureBasisu } from '@gltf-transform/extensions';
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
  doc.createExtension(KHRTextureBasisu).setRequired(true);
  const tex = doc.createTexture('gpu').setMimeType('image/ktx2').setImage(new Uint8Array([0xab, 0x4b, 0x54, 0x58, 0x20, 0x32, 0x30, 0xbb, 0x0d, 0x0a, 0x1a, 0x0a]));
  doc.createScene().addChild(doc.createNode('n').setMesh(quadMesh(doc, doc.createBuffer(), doc.createMaterial().setBaseColorTexture(tex))));
  await bad(await toGlb(doc), '/extensionsRequired/0', /KHR_texture_basisu is not supported/);
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
