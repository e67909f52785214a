// Memory and time bombs end in typed errors before anything large is allocated: accessors without
// data, image headers claiming huge sizes, JSON nesting and value counts, environment-map headers,
// and decoders that loop on corrupt data (three's EXRLoader, run in a worker with a deadline).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { join } from 'node:path';
import { encode as encodePng } from 'fast-png';
import { loadGltfScene, loadEnvironmentMap } from '../../src/index.ts';
import { decodeHdr } from '../../src/io/images/radiance-hdr.ts';
import { assetFolder, refused, triangleDataUri, triangleGltf } from './helpers.ts';

const encoder = new TextEncoder();

/** Runs `body` and asserts it allocated less than `mb` MiB of array buffers and took under `ms`. */
async function bounded(body: () => Promise<unknown>, mb: number, ms: number): Promise<void> {
  const before = process.memoryUsage().arrayBuffers;
  const started = performance.now();
  await body();
  const grown = (process.memoryUsage().arrayBuffers - before) / 2 ** 20;
  assert.ok(grown < mb, `array buffers grew by ${grown.toFixed(0)} MiB`);
  assert.ok(performance.now() - started < ms, `took ${(performance.now() - started).toFixed(0)} ms`);
}

test('an index accessor without a bufferView and count 2^32 is refused before allocation (was 16.5 GB)', async () => {
  const json = triangleGltf(triangleDataUri, {
    accessors: [
      { bufferView: 0, componentType: 5126, count: 3, type: 'VEC3', min: [0, 0, 0], max: [1, 1, 0] },
      { componentType: 5125, count: 2 ** 32, type: 'SCALAR' },
    ],
    meshes: [{ primitives: [{ attributes: { POSITION: 0 }, indices: 1 }] }],
  });
  const bytes = encoder.encode(JSON.stringify(json));
  assert.ok(bytes.length < 600, `${bytes.length} bytes`);
  await bounded(() => refused(loadGltfScene(bytes), 'INVALID_GLTF', '/accessors/1/count', /maxDecodedBytes/), 16, 2000);
  // Many accessors viewing the same megabyte: each becomes its own array, each is charged.
  const megabyte = `data:application/octet-stream;base64,${Buffer.from(new Uint8Array(2 ** 20)).toString('base64')}`;
  const aliased = triangleGltf(megabyte, {
    buffers: [{ uri: megabyte, byteLength: 2 ** 20 }],
    bufferViews: [{ buffer: 0, byteLength: 2 ** 20 }],
    accessors: Array.from({ length: 300 }, () => ({ bufferView: 0, componentType: 5126, count: 87381, type: 'VEC3' })),
  });
  await bounded(() => refused(loadGltfScene(encoder.encode(JSON.stringify(aliased)), { resourcePolicy: { maxDecodedBytes: 2 ** 28 } }), 'INVALID_GLTF', /^\/accessors\/\d+\/count$/, /maxDecodedBytes/), 32, 5000);
});

test('image sizes are read from the header before decoding: a 69-byte PNG claiming 2^31 - 1 columns', async () => {
  const png = encodePng({ width: 1, height: 1, data: new Uint8Array([1, 2, 3, 255]), channels: 4 });
  new DataView(png.buffer, png.byteOffset).setUint32(16, 0x7fffffff); // IHDR width
  assert.ok(png.length < 80);
  const json = triangleGltf(triangleDataUri, {
    images: [{ uri: `data:image/png;base64,${Buffer.from(png).toString('base64')}` }],
    textures: [{ source: 0 }],
    materials: [{ pbrMetallicRoughness: { baseColorTexture: { index: 0 } } }],
    meshes: [{ primitives: [{ attributes: { POSITION: 0 }, material: 0 }] }],
  });
  await bounded(() => refused(loadGltfScene(encoder.encode(JSON.stringify(json))), 'INVALID_GLTF', '/images/0', /2147483647 x 1 texels exceed the largest side of 16384/), 16, 2000);
  // Within the side limit but over the budget: refused by the budget, still before decoding.
  new DataView(png.buffer, png.byteOffset).setUint32(16, 16384);
  new DataView(png.buffer, png.byteOffset).setUint32(20, 16384);
  json.images = [{ uri: `data:image/png;base64,${Buffer.from(png).toString('base64')}` }];
  await bounded(() => refused(loadGltfScene(encoder.encode(JSON.stringify(json)), { resourcePolicy: { maxDecodedBytes: 2 ** 28 } }), 'INVALID_GLTF', '/images/0', /maxDecodedBytes/), 16, 2000);
});

test('JSON nested 100 000 deep or holding millions of values is refused before parsing', async () => {
  const deep = JSON.stringify(triangleGltf(triangleDataUri)).replace('"asset"', `"extras":${'['.repeat(100_000)}${']'.repeat(100_000)},"asset"`);
  await refused(loadGltfScene(encoder.encode(deep)), 'INVALID_GLTF', '', /nests 100001 levels deep/);
  const wide = JSON.stringify(triangleGltf(triangleDataUri)).replace('"asset"', `"extras":[${'{},'.repeat(2_000_000)}{}],"asset"`);
  await refused(loadGltfScene(encoder.encode(wide), { resourcePolicy: { maxDecodedBytes: 2 ** 26 } }), 'INVALID_GLTF', '', /parsing the JSON's \d+ values/);
});

test('a node hierarchy 5000 deep loads (no recursion), and a 100 000-node chain is checked in linear time', async () => {
  const nodes = Array.from({ length: 5000 }, (_, i) => (i < 4999 ? { children: [i + 1] } : { mesh: 0, translation: [1, 2, 3] }));
  const scene = await loadGltfScene(encoder.encode(JSON.stringify(triangleGltf(triangleDataUri, { nodes }))));
  assert.equal(scene.instances.length, 1);
  assert.deepEqual(Array.from(scene.instances[0]!.transform!).slice(12, 15), [1, 2, 3]);
  const long = Array.from({ length: 100_000 }, (_, i) => (i < 99_999 ? { children: [i + 1] } : { mesh: 0 }));
  const started = performance.now();
  assert.equal((await loadGltfScene(encoder.encode(JSON.stringify(triangleGltf(triangleDataUri, { nodes: long }))))).instances.length, 1);
  assert.ok(performance.now() - started < 10_000, `${(performance.now() - started).toFixed(0)} ms`);
});

test('environment maps: /dev/zero, a pipe, a 1e20 .hdr resolution and a 10-byte .exr end in typed errors at once', async () => {
  const f = assetFolder();
  try {
    await refused(loadEnvironmentMap('/dev/zero'), 'INVALID_ENVIRONMENT', 'source', /character device/, 2000);
    await refused(loadEnvironmentMap(f.asset), 'INVALID_ENVIRONMENT', 'source', /directory/, 2000);
    const hdr = encoder.encode('#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 100000000000000000000 +X 8\n\x80\x80\x80\x81');
    await bounded(() => refused(loadEnvironmentMap(hdr), 'INVALID_ENVIRONMENT', 'source', /exceed the largest map side of 8192/), 16, 1000);
    assert.throws(() => decodeHdr(hdr), (e: Error & { field?: string }) => e.field === 'bytes' && /exceed the largest side/.test(e.message));
    // Truncated: three's EXRLoader loops forever reading the header past the end.
    const exr = new Uint8Array([0x76, 0x2f, 0x31, 0x01, 2, 0, 0, 0, 0x63, 0x68]);
    await refused(loadEnvironmentMap(exr), 'INVALID_ENVIRONMENT', 'source', /NUL-terminated|no terminating NUL/, 2000);
    const path = join(f.asset, 'tiny.exr');
    writeFileSync(path, exr);
    await refused(loadEnvironmentMap(path), 'INVALID_ENVIRONMENT', 'source', /OpenEXR/, 2000);
  } finally {
    f.cleanup();
  }
});

test('an OpenEXR whose compressed data makes the decoder loop ends at the decode deadline', async () => {
  // A real DWAB map with 62 bytes of its data overwritten: three's Huffman decoder never returns.
  const require = createRequire(import.meta.url);
  const text = readFileSync(require.resolve('@pmndrs/assets/hdri/sunset.exr.js'), 'utf8');
  const bytes = new Uint8Array(Buffer.from(/base64,([^'"]+)/.exec(text)![1]!, 'base64'));
  bytes.fill(0xff, 32255, 32255 + 62);
  await refused(loadEnvironmentMap(bytes, { resourcePolicy: { decodeTimeoutMs: 1500 } }), 'INVALID_ENVIRONMENT', 'source', /did not finish within 1500 ms/, 5000);
  // The intact file decodes (in the worker) to the map it holds.
  bytes.set(new Uint8Array(Buffer.from(/base64,([^'"]+)/.exec(text)![1]!, 'base64')).subarray(32255, 32255 + 62), 32255);
  const map = await loadEnvironmentMap(bytes, { negativeTexels: 'zero' });
  assert.deepEqual([map.width, map.height], [512, 256]);
});
