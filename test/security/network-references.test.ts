// The network is reached only where the caller allows it: an asset fetched from a URL reads inside
// its own folder; other origins need resourcePolicy.allowedOrigins, also from a scene file and
// through redirects; fetches have a timeout and a size cap; an AbortSignal ends them at once.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { loadGltfScene, loadSceneFile } from '../../src/io/index.ts';
import { assetFolder, recordingServer, refused, TRIANGLE, triangleGltf } from './helpers.ts';

test('an asset fetched over http reads its own folder, never file: or other origins unasked', async () => {
  const other = await recordingServer((_req, res) => (res.end(TRIANGLE), true));
  const assets = new Map<string, string>();
  const server = await recordingServer((req, res) => {
    const body = assets.get(req.url ?? '');
    if (body === undefined) return false;
    res.end(body === 'TRIANGLE' ? TRIANGLE : body);
    return true;
  });
  const f = assetFolder();
  try {
    assets.set('/models/tri.bin', 'TRIANGLE');
    assets.set('/models/ok.gltf', JSON.stringify(triangleGltf('tri.bin')));
    assets.set('/models/file.gltf', JSON.stringify(triangleGltf(`file://${f.canary}`)));
    assets.set('/models/up.gltf', JSON.stringify(triangleGltf('../secret/tri.bin')));
    assets.set('/models/other.gltf', JSON.stringify(triangleGltf(`${other.origin}/internal-admin?x=1`)));
    assert.equal((await loadGltfScene(`${server.origin}/models/ok.gltf`)).meshes.length, 1);
    await refused(loadGltfScene(`${server.origin}/models/file.gltf`), 'INVALID_GLTF', '/buffers/0', /file: URIs are not read/);
    await refused(loadGltfScene(`${server.origin}/models/up.gltf`), 'INVALID_GLTF', '/buffers/0', /outside the asset's folder/);
    await refused(loadGltfScene(`${server.origin}/models/other.gltf`), 'INVALID_GLTF', '/buffers/0', /allowedOrigins/);
    assert.deepEqual(other.requests, [], 'the other origin was contacted without permission');
    assert.equal(f.canaryRead(), false);
    // Allowed explicitly: fetched.
    assert.equal((await loadGltfScene(`${server.origin}/models/other.gltf`, { resourcePolicy: { allowedOrigins: [other.origin] } })).meshes.length, 1);
    assert.deepEqual(other.requests, ['/internal-admin?x=1']);
  } finally {
    other.close();
    server.close();
    f.cleanup();
  }
});

test("a scene file's http references need an allowed origin; redirects may not leave what is allowed", async () => {
  const target = await recordingServer((_req, res) => (res.end(TRIANGLE), true));
  const allowed = await recordingServer((req, res) => {
    if (req.url === '/redirect.bin') {
      res.writeHead(302, { location: `${target.origin}/internal-admin?x=1` });
      res.end();
      return true;
    }
    if (req.url === '/model.gltf') return (res.end(JSON.stringify(triangleGltf('redirect.bin'))), true);
    return false;
  });
  const f = assetFolder();
  try {
    const scene = join(f.asset, 'scene.json');
    writeFileSync(scene, JSON.stringify({ gltf: [{ src: `${target.origin}/internal-admin?x=1` }] }));
    await refused(loadSceneFile(scene), 'INVALID_SCENE_FILE', 'gltf[0].src', /allowedOrigins/);
    writeFileSync(scene, JSON.stringify({ gltf: [{ src: `${allowed.origin}/model.gltf` }] }));
    await refused(loadSceneFile(scene, { resourcePolicy: { allowedOrigins: [allowed.origin] } }), 'INVALID_GLTF', '/buffers/0', /redirects to .*where this load may not go/);
    assert.deepEqual(target.requests, [], 'a redirect reached an origin that was not allowed');
    assert.deepEqual(allowed.requests, ['/model.gltf', '/redirect.bin']);
  } finally {
    target.close();
    allowed.close();
    f.cleanup();
  }
});

test('fetches end at the timeout, at the size cap, and when the signal aborts', async () => {
  const server = await recordingServer((req, res) => {
    if (req.url?.startsWith('/slow')) return true; // never answered
    if (req.url === '/huge.glb') {
      res.writeHead(200);
      const chunk = new Uint8Array(1 << 16);
      const pump = (): void => {
        while (res.write(chunk));
      };
      res.on('drain', pump);
      pump();
      return true;
    }
    return false;
  });
  try {
    await refused(loadGltfScene(`${server.origin}/slow.glb`, { resourcePolicy: { fetchTimeoutMs: 300 } }), 'INVALID_GLTF', '', /no complete response within 300 ms/, 3000);
    await refused(loadGltfScene(`${server.origin}/huge.glb`, { resourcePolicy: { maxResourceBytes: 1 << 20 } }), 'INVALID_GLTF', '', /more than the resource limit/, 5000);
    const controller = new AbortController();
    const started = performance.now();
    setTimeout(() => controller.abort(), 200);
    await assert.rejects(loadGltfScene(`${server.origin}/slow-abort.glb`, { signal: controller.signal }), { name: 'AbortError' });
    assert.ok(performance.now() - started < 2000, 'the abort did not end the fetch promptly');
  } finally {
    server.close();
  }
});
