import { test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtemp, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { Document } from '@gltf-transform/core';
import { KHRLightsPunctual } from '@gltf-transform/extensions';
import { encode as encodePng } from 'fast-png';
import { resolveGltfReferences } from '../../../src/io/index.ts';
import { parseGltfReferences } from '../../../src/scene/index.ts';
import { GpuRendererError } from '../../../src/errors/gpu-renderer-error.ts';
import { assertClose, quadMesh, rejectsWith, toGlb } from './helpers.ts';

test('parseGltfReferences: strings, objects, and typed errors naming the key', () => {
  assert.deepEqual(parseGltfReferences('a.glb'), [{ src: 'a.glb' }]);
  assert.deepEqual(parseGltfReferences([{ src: 'b.gltf', camera: 'top', variant: 'Night', scene: 1 }]), [{ src: 'b.gltf', camera: 'top', variant: 'Night', scene: 1 }]);
  const fails = (value: unknown, field: string): void =>
    assert.throws(() => parseGltfReferences(value), (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_SCENE_FILE' && e.field === field);
  fails([{ src: 'a.glb', colour: 1 }], 'gltf[0].colour');
  fails({ src: 3 }, 'gltf.src');
  fails([{ src: 'a.glb', transform: [1, 2] }], 'gltf[0].transform');
  fails([{ src: 'a.glb', transform: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 'x', 1] }], 'gltf[0].transform[14]');
  fails([{ src: 'a.glb', transform: [0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1] }], 'gltf[0].transform');
});

test('resolveGltfReferences merges assets with offset indices and placed instances, lights and camera', async () => {
  const doc = new Document();
  const tex = doc.createTexture('t').setMimeType('image/png').setImage(encodePng({ width: 1, height: 1, data: new Uint8Array([1, 2, 3, 255]), channels: 4 }));
  const light = doc.createExtension(KHRLightsPunctual).createLight('l').setType('point');
  doc.createScene()
    .addChild(doc.createNode('q').setMesh(quadMesh(doc, doc.createBuffer(), doc.createMaterial('m').setBaseColorTexture(tex))).setTranslation([1, 0, 0]))
    .addChild(doc.createNode('lamp').setTranslation([0, 2, 0]).setExtension('KHR_lights_punctual', light));
  const dir = await mkdtemp(join(tmpdir(), 'gltf-ref-'));
  try {
    await writeFile(join(dir, 'model.glb'), await toGlb(doc));
    const base = {
      meshes: [{ positions: [0, 0, 0, 1, 0, 0, 0, 1, 0], material: 0 }],
      materials: [{ baseColorFactor: [0.5, 0.5, 0.5] }],
      textures: [{ image: { width: 1, height: 1, data: new Uint8Array(4) } }],
    };
    const shift = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 10, 0, 0, 1];
    const refs = parseGltfReferences(['model.glb', { src: 'model.glb', transform: shift }]);
    const { scene } = await resolveGltfReferences(base, refs, { base: join(dir, 'scene.json') });
    assert.equal(scene.meshes!.length, 3);
    assert.equal(scene.materials!.length, 3);
    assert.deepEqual(scene.meshes!.map((m) => m.material), [0, 1, 2]);
    assert.equal(scene.materials![1].baseColorTexture!.index, 1, 'texture indices offset past the file\'s own');
    assert.equal(scene.materials![2].baseColorTexture!.index, 2);
    assert.deepEqual(scene.textures!.slice(1).map((t) => t.image), [0, 1]);
    assert.equal(scene.images!.length, 2);
    // The file's own mesh gets an identity instance; the assets' instances are offset and placed.
    assert.deepEqual(scene.instances!.map((i) => i.mesh), [0, 1, 2]);
    assert.equal(scene.instances![0].transform, undefined);
    assertClose(scene.instances![1].transform!, [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 1], 0, 'first');
    assertClose(scene.instances![2].transform!, [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 11, 0, 0, 1], 0, 'second');
    assertClose(scene.lights![1].position!, [10, 2, 0], 0, 'light placed by the transform');
    assert.ok(scene.camera !== undefined, 'camera from the first reference');

    await rejectsWith(resolveGltfReferences(base, [{ src: 'missing.glb' }], { base: join(dir, 'scene.json') }), 'INVALID_GLTF', 'gltf[0].src', /in gltf\[0\] \("missing.glb"\): cannot read/);
  } finally {
    await rm(dir, { recursive: true, force: true });
  }
});
