// Scene JSON files with external resources: images by uri (relative to the file, or data URIs) are
// decoded, glTF references merged, and missing or broken resources are typed errors naming the field.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtempSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { Document } from '@gltf-transform/core';
import { encode } from 'fast-png';
import { loadSceneFile } from '../../src/io/scene-file-loader.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { quadMesh, toGlb } from './gltf/helpers.ts';

const pixels = Uint8Array.from([255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 128]);

function writeScene(dir: string, scene: unknown): string {
  const path = join(dir, 'scene.json');
  writeFileSync(path, JSON.stringify(scene));
  return path;
}

test('images by relative uri and by data URI decode to the same RGBA8 texels', async () => {
  const dir = mkdtempSync(join(tmpdir(), 'scene-file-'));
  const png = encode({ width: 2, height: 2, data: pixels, channels: 4 });
  writeFileSync(join(dir, 'checker.png'), png);
  const dataUri = `data:image/png;base64,${Buffer.from(png).toString('base64')}`;
  const path = writeScene(dir, {
    images: [{ uri: 'checker.png' }, { uri: dataUri }],
    textures: [{ image: 0 }, { image: 1 }],
    meshes: [{ positions: [0, 0, 0, 1, 0, 0, 0, 1, 0], uvs: [0, 0, 1, 0, 0, 1], material: { baseColorTexture: { index: 1 } } }],
  });
  const { scene } = await loadSceneFile(path);
  for (const image of scene.images!) {
    assert.equal(image.width, 2);
    assert.equal(image.height, 2);
    assert.deepEqual(Array.from(image.data), Array.from(pixels));
  }
});

test('glTF references merge the asset after the file content, placed by their transform', async () => {
  const dir = mkdtempSync(join(tmpdir(), 'scene-file-'));
  const document = new Document();
  const buffer = document.createBuffer();
  const node = document.createNode('quad').setMesh(quadMesh(document, buffer));
  document.createScene('scene').addChild(node);
  writeFileSync(join(dir, 'quad.glb'), await toGlb(document));
  const path = writeScene(dir, {
    meshes: [{ positions: [0, 0, 0, 1, 0, 0, 0, 1, 0] }],
    gltf: [{ src: 'quad.glb', transform: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 0, 0, 1] }],
  });
  const { scene } = await loadSceneFile(path);
  assert.equal(scene.meshes!.length, 2, "the file's triangle and the asset's quad");
  assert.deepEqual(scene.instances!.map((i) => i.mesh), [0, 1]);
  assert.equal(scene.instances![1]!.transform![12], 5, 'the reference transform places the asset');
});

test('missing or undecodable resources are typed errors naming the field', async () => {
  const dir = mkdtempSync(join(tmpdir(), 'scene-file-'));
  writeFileSync(join(dir, 'not-an-image.png'), 'hello');
  const rejects = async (scene: unknown, field: string): Promise<void> => {
    await assert.rejects(loadSceneFile(writeScene(dir, scene)), (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_SCENE_FILE' && e.field === field);
  };
  await rejects({ images: [{ uri: 'missing.png' }] }, 'images[0].uri');
  await rejects({ images: [{ width: 1, height: 1, data: [0, 0, 0, 0] }, { uri: 'not-an-image.png' }] }, 'images[1].uri');
  await rejects({ images: [{ uri: 'a.png', width: 2 }] }, 'images[0]');
  await rejects({ gltf: [{ src: 'x.glb', scale: 2 }] }, 'gltf[0].scale');
  await assert.rejects(loadSceneFile(join(dir, 'nothing.json')), (e: unknown) => e instanceof GpuRendererError && e.field === 'scene');
  // A referenced glTF that cannot be read is named by its reference.
  await assert.rejects(loadSceneFile(writeScene(dir, { gltf: [{ src: 'missing.glb' }] })), (e: unknown) => e instanceof GpuRendererError && e.field === 'gltf[0].src');
});
