// A glTF may only read inside its own folder: traversal (plain, percent-encoded, backslashed),
// absolute paths, file: URLs, /proc, devices, pipes and symbolic links leaving the folder are typed
// errors at the JSON pointer, and the canary beside the folder is never read. Sources the caller
// names are read only when they are regular files.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { mkdirSync, symlinkSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';
import { loadGltfScene } from '../../src/io/index.ts';
import { assetFolder, refused, TRIANGLE, triangleDataUri, triangleGltf } from './helpers.ts';

test('references that leave the asset folder are refused and nothing outside is read', async () => {
  const f = assetFolder();
  try {
    symlinkSync('../canary.bin', join(f.asset, 'link-out'));
    symlinkSync('..', join(f.asset, 'link-up'));
    const hostile: Array<[string, RegExp]> = [
      ['../canary.bin', /outside the asset's folder/],
      ['sub/../../canary.bin', /outside the asset's folder/],
      ['%2e%2e/canary.bin', /outside the asset's folder/],
      ['.%2E/canary.bin', /outside the asset's folder/],
      ['..\\canary.bin', /outside the asset's folder/],
      ['..%2fcanary.bin', /hides a path separator/],
      ['..%5Ccanary.bin', /hides a path separator/],
      [f.canary, /absolute path/],
      [pathToFileURL(f.canary).href, /file: URIs are not read/],
      ['file:canary.bin', /file: URIs are not read/],
      ['/proc/self/environ', /absolute path/],
      ['/etc/passwd', /absolute path/],
      ['C:\\Windows\\win.ini', /absolute path/],
      ['link-out', /symbolic link.*outside the folder/],
      ['link-up/canary.bin', /symbolic link.*outside the folder/],
    ];
    for (const [uri, message] of hostile) {
      const path = join(f.asset, 'scene.gltf');
      writeFileSync(path, JSON.stringify(triangleGltf(uri)));
      await refused(loadGltfScene(path), 'INVALID_GLTF', '/buffers/0', message);
      // As an image reference too.
      writeFileSync(path, JSON.stringify({ ...triangleGltf(triangleDataUri), images: [{ uri }] }));
      await refused(loadGltfScene(path), 'INVALID_GLTF', '/images/0', message);
    }
    assert.equal(f.canaryRead(), false, 'the canary outside the folder was read');
  } finally {
    f.cleanup();
  }
});

test('references inside the folder load, through subfolders, encoded names and inner links', async () => {
  const f = assetFolder();
  try {
    writeFileSync(join(f.asset, 'sub', 'tri angle.bin'), TRIANGLE);
    symlinkSync('sub/tri angle.bin', join(f.asset, 'link-in'));
    for (const uri of ['sub/tri%20angle.bin', './sub/../sub/tri%20angle.bin', 'link-in', 'sub%2Ftri%20angle.bin'.replace('%2F', '/')]) {
      const path = join(f.asset, 'scene.gltf');
      writeFileSync(path, JSON.stringify(triangleGltf(uri)));
      const scene = await loadGltfScene(path);
      assert.deepEqual(Array.from(scene.meshes[0]!.positions), [0, 0, 0, 1, 0, 0, 0, 1, 0], uri);
    }
  } finally {
    f.cleanup();
  }
});

test('devices, pipes, folders and pseudo-files are refused, as references and as sources, without blocking', async () => {
  const f = assetFolder();
  try {
    execFileSync('mkfifo', [join(f.asset, 'fifo')]);
    symlinkSync('/dev/zero', join(f.asset, 'zero'));
    const path = join(f.asset, 'scene.gltf');
    // A reference that is a named pipe inside the folder: refused before opening (a reader would block).
    writeFileSync(path, JSON.stringify(triangleGltf('fifo')));
    await refused(loadGltfScene(path), 'INVALID_GLTF', '/buffers/0', /named pipe/, 2000);
    writeFileSync(path, JSON.stringify(triangleGltf('sub')));
    await refused(loadGltfScene(path), 'INVALID_GLTF', '/buffers/0', /directory/, 2000);
    // A link to /dev/zero leaves the folder (and is a device): 10 GB read in 55 s before.
    writeFileSync(path, JSON.stringify(triangleGltf('zero')));
    await refused(loadGltfScene(path), 'INVALID_GLTF', '/buffers/0', /outside the folder/, 2000);
    // The caller's own source must be a regular file too.
    await refused(loadGltfScene('/dev/zero'), 'INVALID_GLTF', '', /character device/, 2000);
    await refused(loadGltfScene(join(f.asset, 'fifo')), 'INVALID_GLTF', '', /named pipe/, 2000);
    await refused(loadGltfScene(f.asset), 'INVALID_GLTF', '', /directory/, 2000);
    await refused(loadGltfScene('/proc/self/environ'), 'INVALID_GLTF', '', /pseudo-file/, 2000);
  } finally {
    f.cleanup();
  }
});

test('resourcePolicy.root confines the references too: an asset whose folder links out of the root reads nothing there', async () => {
  const f = assetFolder();
  try {
    // asset/linked -> ../outside; outside/scene.gltf -> the real asset inside the root; outside/tri.bin beside it.
    const outside = join(f.root, 'outside');
    mkdirSync(outside);
    writeFileSync(join(outside, 'tri.bin'), TRIANGLE);
    writeFileSync(join(f.asset, 'scene-real.gltf'), JSON.stringify(triangleGltf('tri.bin')));
    symlinkSync(join(f.asset, 'scene-real.gltf'), join(outside, 'scene.gltf'));
    symlinkSync(outside, join(f.asset, 'linked'));
    const path = join(f.asset, 'linked', 'scene.gltf');
    // Without a root the reference stays in the asset's folder (outside/), so it loads.
    assert.equal((await loadGltfScene(path)).meshes.length, 1);
    await refused(loadGltfScene(path, { resourcePolicy: { root: f.asset } }), 'INVALID_GLTF', '/buffers/0', /symbolic link.*outside the folder/);
  } finally {
    f.cleanup();
  }
});

test('bytes keep refusing external references; resourcePolicy.root confines the source', async () => {
  const f = assetFolder();
  try {
    writeFileSync(join(f.asset, 'tri.bin'), TRIANGLE);
    const json = new TextEncoder().encode(JSON.stringify(triangleGltf('tri.bin')));
    await refused(loadGltfScene(json), 'INVALID_GLTF', '/buffers/0', /given as bytes/);
    const path = join(f.asset, 'scene.gltf');
    writeFileSync(path, json);
    assert.equal((await loadGltfScene(path, { resourcePolicy: { root: f.asset } })).meshes.length, 1);
    await refused(loadGltfScene(path, { resourcePolicy: { root: join(f.root, 'elsewhere') } }), 'INVALID_GLTF', '', /outside the resource policy's root/);
    await refused(loadGltfScene(path, { resourcePolicy: { allowedOrigins: ['https://cdn.example.com/models'] } }), 'INVALID_OPTION', 'resourcePolicy.allowedOrigins[0]', /without path/);
    await refused(loadGltfScene(path, { resourcePolicy: { maxDecodedBytes: -1 } }), 'INVALID_OPTION', 'resourcePolicy.maxDecodedBytes');
    await refused(loadGltfScene(path, { resourcePolicy: { maxResourceBytes: 100 } }), 'INVALID_GLTF', '', /resource limit of 100/);
  } finally {
    f.cleanup();
  }
});
