// The CLI's resource policy: a scene's references stay in its folder and reach the network only
// for the origins --allow-origin names (the renderer is not started for a refused scene).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { parseRenderArgs } from '../../src/cli/args.ts';
import { loadScene } from '../../src/cli/render-command.ts';
import { runCli } from '../helpers/cli-process.ts';
import { assetFolder, recordingServer, refused, TRIANGLE, triangleGltf } from './helpers.ts';

test('--allow-origin: repeatable, comma separated, origins only', () => {
  const command = parseRenderArgs(['scene.json', '--allow-origin', 'https://a.example, http://127.0.0.1:8080', '--allow-origin=https://b.example:8443']);
  assert.ok(command.kind === 'render');
  assert.deepEqual(command.allowedOrigins, ['https://a.example', 'http://127.0.0.1:8080', 'https://b.example:8443']);
  assert.throws(() => parseRenderArgs(['--allow-origin', 'https://a.example/models']), (e: Error & { field?: string }) => e.field === '--allow-origin' && /without path/.test(e.message));
  assert.throws(() => parseRenderArgs(['--allow-origin', 'file:///etc']), (e: Error & { field?: string }) => e.field === '--allow-origin' && /only http and https/.test(e.message));
});

test("a scene's remote glTF is refused without --allow-origin and loaded with it", async () => {
  const server = await recordingServer((req, res) => {
    if (req.url === '/tri.gltf') return (res.end(JSON.stringify(triangleGltf('tri.bin'))), true);
    if (req.url === '/tri.bin') return (res.end(TRIANGLE), true);
    return false;
  });
  const f = assetFolder();
  try {
    const scene = join(f.asset, 'scene.json');
    writeFileSync(scene, JSON.stringify({ gltf: [{ src: `${server.origin}/tri.gltf` }] }));
    const r = await runCli(['render', scene, '--width', '4', '--height', '4', '--spp', '1', '--out', join(f.root, 'out.png')]);
    assert.equal(r.code, 1);
    assert.match(r.stderr, /^error \[INVALID_SCENE_FILE\] gltf\[0\]\.src: .*allowedOrigins; CLI --allow-origin/);
    assert.deepEqual(server.requests, []);
    await refused(loadScene(scene, { resourcePolicy: { allowedOrigins: [] } }), 'INVALID_SCENE_FILE', 'gltf[0].src');
    const loaded = await loadScene(scene, { resourcePolicy: { allowedOrigins: [server.origin] } });
    assert.equal(loaded.meshes!.length, 1);
    assert.deepEqual(server.requests, ['/tri.gltf', '/tri.bin']);
  } finally {
    server.close();
    f.cleanup();
  }
});
