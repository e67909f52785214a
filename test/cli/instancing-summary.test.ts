// The render summary says how the geometry is stored: a glTF of 300 EXT_mesh_gpu_instancing
// placements of a 1,280-triangle sphere is traced through one shared mesh ('auto'), and
// --instancing off flattens the same placements (384,000 triangles) into the top level.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtemp, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { Document, NodeIO } from '@gltf-transform/core';
import { ALL_EXTENSIONS, EXTMeshGPUInstancing } from '@gltf-transform/extensions';
import { describeGeometry } from '../../src/cli/render-format.ts';
import { runCli } from '../helpers/cli-process.ts';
import { icosphere } from '../helpers/meshes.ts';

const run = runCli;

async function instancedGlb(count: number): Promise<Uint8Array> {
  const doc = new Document();
  const buffer = doc.createBuffer();
  const sphere = icosphere(0.3, [0, 0, 0], 3);
  const acc = (type: 'VEC3' | 'VEC4', values: number[]) => doc.createAccessor().setType(type).setArray(new Float32Array(values)).setBuffer(buffer);
  const primitive = doc
    .createPrimitive()
    .setAttribute('POSITION', acc('VEC3', sphere.positions))
    .setIndices(doc.createAccessor().setType('SCALAR').setArray(new Uint32Array(sphere.indices)).setBuffer(buffer))
    .setMaterial(doc.createMaterial('white').setBaseColorFactor([0.8, 0.8, 0.8, 1]).setMetallicFactor(0).setRoughnessFactor(1));
  const batch = doc
    .createExtension(EXTMeshGPUInstancing)
    .setRequired(true)
    .createInstancedMesh()
    .setAttribute('TRANSLATION', acc('VEC3', Array.from({ length: count }, (_, i) => [(i % 20) - 10, Math.floor(i / 20) - 7, 0]).flat()));
  doc
    .createScene()
    .addChild(doc.createNode('spheres').setMesh(doc.createMesh('sphere').addPrimitive(primitive)).setExtension('EXT_mesh_gpu_instancing', batch))
    .addChild(doc.createNode('eye').setCamera(doc.createCamera('eye').setType('perspective').setYFov(1).setZNear(0.1)).setTranslation([0, 0, 20]));
  return new NodeIO().registerExtensions(ALL_EXTENSIONS).writeBinary(doc);
}

test('the render summary names the placements of shared meshes, or the flattened triangles with --instancing off', async () => {
  const dir = await mkdtemp(join(tmpdir(), 'gpu-renderer-instancing-'));
  try {
    const scene = join(dir, 'spheres.glb');
    await writeFile(scene, await instancedGlb(300));
    const shared = await run(['render', scene, '--out', join(dir, 'a.png'), '--width', '16', '--height', '16', '--spp', '1']);
    assert.equal(shared.code, 0, shared.stderr);
    assert.match(shared.stderr, /geometry: 300 placements of 1 shared mesh \(1\.28 k triangles stored once for 384 k placed, \d+ bytes per placement\), 0 triangles flattened \(--instancing auto\); scene buffers [\d.]+ MiB/);
    const flat = await run(['render', scene, '--out', join(dir, 'b.png'), '--width', '16', '--height', '16', '--spp', '1', '--instancing', 'off']);
    assert.equal(flat.code, 0, flat.stderr);
    assert.match(flat.stderr, /geometry: 384 k triangles flattened \(--instancing off\)/);
    const bad = await run(['render', scene, '--out', join(dir, 'c.png'), '--instancing', 'sometimes']);
    assert.notEqual(bad.code, 0);
    assert.match(bad.stderr, /--instancing/);
  } finally {
    await rm(dir, { recursive: true, force: true });
  }
});

test('describeGeometry: placements, stored and placed triangles, bytes per placement, scene memory', () => {
  const line = describeGeometry({
    instancing: { mode: 'auto', sharedMeshes: 2, placements: 10_000, bottomLevelTriangles: 40_960, placedTriangles: 204_800_000, flattenedTriangles: 2, topLevelRecords: 10_002, bytesPerPlacement: 312 },
    memory: { sceneBytes: 12 * 2 ** 20, textureBytes: 0, queueBytes: 0, frameBytes: 0, totalBytes: 0 },
  });
  assert.equal(line, 'geometry: 10.0 k placements of 2 shared meshes (41.0 k triangles stored once for 205 M placed, 312 bytes per placement), 2 triangles flattened (--instancing auto); scene buffers 12.0 MiB');
});
