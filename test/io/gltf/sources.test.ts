// Every kind of source: .gltf path with external resources, file: URL, http URL on a loopback
// server, ArrayBuffer, Uint8Array, and a @gltf-transform Document.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createServer } from 'node:http';
import { mkdir, mkdtemp, readFile, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';
import { Document } from '@gltf-transform/core';
import { encode as encodePng } from 'fast-png';
import { loadGltfScene } from '../../../src/io/index.ts';
import { createIO, quadMesh, rejectsWith, toGlb } from './helpers.ts';

function texturedDoc(): Document {
  const doc = new Document();
  const tex = doc.createTexture('t').setMimeType('image/png').setImage(encodePng({ width: 1, height: 1, data: new Uint8Array([10, 20, 30, 255]), channels: 4 })).setURI('my textures/t.png');
  doc.createScene().addChild(doc.createNode('n').setMesh(quadMesh(doc, doc.createBuffer().setURI('geo.bin'), doc.createMaterial('m').setBaseColorTexture(tex))));
  return doc;
}

async function writeGltfDir(dir: string): Promise<string> {
  const { json, resources } = await createIO().writeJSON(texturedDoc());
  await mkdir(join(dir, 'my textures'), { recursive: true });
  for (const [uri, bytes] of Object.entries(resources)) await writeFile(join(dir, uri), bytes);
  // URIs are URI references (RFC 3986): exporters percent-encode the space.
  json.images![0].uri = encodeURI(json.images![0].uri!);
  const path = join(dir, 'scene.gltf');
  await writeFile(path, JSON.stringify(json));
  return path;
}

function checkTextured(scene: Awaited<ReturnType<typeof loadGltfScene>>): void {
  assert.equal(scene.meshes.length, 1);
  assert.deepEqual([...scene.images[0].data], [10, 20, 30, 255]);
}

test('.gltf path and file: URL with external buffer and image (URI-encoded space)', async () => {
  const dir = await mkdtemp(join(tmpdir(), 'gltf-src-'));
  try {
    const path = await writeGltfDir(dir);
    const json = JSON.parse(await readFile(path, 'utf8'));
    assert.equal(json.images[0].uri, 'my%20textures/t.png');
    checkTextured(await loadGltfScene(path));
    checkTextured(await loadGltfScene(pathToFileURL(path)));
    checkTextured(await loadGltfScene(pathToFileURL(path).href));
    await rejectsWith(loadGltfScene(join(dir, 'nope.glb')), 'INVALID_GLTF', '', /cannot read/);
    // The same JSON as bytes cannot resolve its external files.
    await rejectsWith(loadGltfScene(await readFile(path)), 'INVALID_GLTF', '/buffers/0', /pass a path or URL/);
  } finally {
    await rm(dir, { recursive: true, force: true });
  }
});

test('http URL: the asset and its relative resources are fetched', async () => {
  const dir = await mkdtemp(join(tmpdir(), 'gltf-http-'));
  const server = createServer((req, res) => {
    readFile(join(dir, decodeURIComponent(new URL(req.url!, 'http://x').pathname)))
      .then((body) => res.end(body))
      .catch(() => ((res.statusCode = 404), res.end()));
  });
  try {
    await writeGltfDir(dir);
    await new Promise<void>((resolve) => server.listen(0, '127.0.0.1', resolve));
    const { port } = server.address() as { port: number };
    checkTextured(await loadGltfScene(`http://127.0.0.1:${port}/scene.gltf`));
    await rejectsWith(loadGltfScene(`http://127.0.0.1:${port}/missing.glb`), 'INVALID_GLTF', '', /HTTP 404/);
  } finally {
    server.close();
    await rm(dir, { recursive: true, force: true });
  }
});

test('ArrayBuffer, Uint8Array view at an offset, and Document sources', async () => {
  const doc = texturedDoc();
  const glb = await toGlb(doc);
  checkTextured(await loadGltfScene(glb.slice().buffer));
  const padded = new Uint8Array(glb.length + 8);
  padded.set(glb, 8);
  checkTextured(await loadGltfScene(padded.subarray(8)));
  const scene = await loadGltfScene(doc);
  checkTextured(scene);
  assert.equal(scene.document, doc);
});

test('an aborted signal stops loading', async () => {
  const controller = new AbortController();
  controller.abort();
  await assert.rejects(loadGltfScene(await toGlb(texturedDoc()), { signal: controller.signal }), { name: 'AbortError' });
});
