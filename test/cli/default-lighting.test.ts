// A scene with no light of any kind and no --env is lit by the built-in neutral environment, and the
// summary says how every scene was lit; --env none renders with no light.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtemp, readFile, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { Document, NodeIO } from '@gltf-transform/core';
import { ALL_EXTENSIONS, KHRLightsPunctual } from '@gltf-transform/extensions';
import { decode } from 'fast-png';
import { applyCliLighting, NEUTRAL_LIGHTING_SUMMARY } from '../../src/cli/scene-lighting.ts';
import { loadGltfScene } from '../../src/io/gltf/load-gltf-scene.ts';
import { createCornellBoxScene } from '../../src/scene/cornell-box.ts';
import { isGpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { runCli } from '../helpers/cli-process.ts';


const run = runCli;

/** A white quad facing a camera node 3 units away on +Z; a point light when `lit`. */
function quadDocument(lit = false): Document {
  const doc = new Document();
  const buffer = doc.createBuffer();
  const acc = (type: 'VEC3' | 'SCALAR', array: Float32Array<ArrayBuffer> | Uint16Array<ArrayBuffer>) => doc.createAccessor().setType(type).setArray(array).setBuffer(buffer);
  const primitive = doc
    .createPrimitive()
    .setAttribute('POSITION', acc('VEC3', new Float32Array([-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0])))
    .setIndices(acc('SCALAR', new Uint16Array([0, 1, 2, 0, 2, 3])))
    .setMaterial(doc.createMaterial('white').setBaseColorFactor([0.8, 0.8, 0.8, 1]).setMetallicFactor(0).setRoughnessFactor(1));
  const scene = doc
    .createScene()
    .addChild(doc.createNode('quad').setMesh(doc.createMesh('quad').addPrimitive(primitive)))
    .addChild(doc.createNode('eye').setCamera(doc.createCamera('eye').setType('perspective').setYFov(1).setZNear(0.1)).setTranslation([0, 0, 3]));
  if (lit) {
    const light = doc.createExtension(KHRLightsPunctual).createLight('bulb').setType('point').setIntensity(10);
    scene.addChild(doc.createNode('bulb').setExtension('KHR_lights_punctual', light).setTranslation([0, 0, 2]));
  }
  return doc;
}

test('applyCliLighting: the neutral default only where nothing lights the scene; --env none removes every environment', async () => {
  const bare = { ...(await loadGltfScene(quadDocument())) };
  const defaulted = await applyCliLighting(bare, {});
  assert.equal(defaulted.lighting, NEUTRAL_LIGHTING_SUMMARY);
  assert.ok(defaulted.scene.environmentMap !== undefined && defaulted.scene.environmentMap.data.some((v) => v > 0));
  // --env-intensity and --env-rotation apply to the default map.
  const scaled = await applyCliLighting(bare, { envIntensity: 2, envRotationDegrees: 90 });
  assert.equal(scaled.scene.environmentMap?.intensity, 2);
  assert.equal(scaled.scene.environmentMap?.rotationRadians, Math.PI / 2);

  const none = await applyCliLighting(bare, { env: 'none' });
  assert.equal(none.scene.environmentMap, undefined);
  assert.equal(none.lighting, 'unlit: --env none and the scene has no light of its own (the image is black)');

  const lamp = { ...(await loadGltfScene(quadDocument(true))) };
  const own = await applyCliLighting(lamp, {});
  assert.equal(own.scene.environmentMap, undefined);
  assert.equal(own.lighting, "lit by the scene's 1 punctual light");

  const cornell = await applyCliLighting(createCornellBoxScene(), { env: 'none' });
  assert.equal(cornell.lighting, "lit by the scene's emissive surfaces (--env none: no environment)");
  const uniform = await applyCliLighting({ environment: { color: [1, 1, 1] } }, { env: 'none' });
  assert.equal(uniform.scene.environment, undefined);
  assert.equal(uniform.lighting, 'unlit: --env none and the scene has no light of its own (the image is black)');
  assert.equal((await applyCliLighting({ environment: { color: [0.5, 0.5, 0.5] } }, {})).lighting, "lit by the scene's uniform environment colour");
});

test("loadGltfScene's defaultLighting: 'neutral' lights an asset that has no light, and nothing else", async () => {
  const bare = await loadGltfScene(quadDocument(), { defaultLighting: 'neutral' });
  assert.ok(bare.environmentMap !== undefined && bare.environmentMap.width === 512);
  assert.equal((await bare.pose({})).environmentMap, bare.environmentMap, 'posing again keeps the same map');
  assert.equal((await loadGltfScene(quadDocument())).environmentMap, undefined, "the default is 'none'");
  assert.equal((await loadGltfScene(quadDocument(true), { defaultLighting: 'neutral' })).environmentMap, undefined);
  await assert.rejects(loadGltfScene(quadDocument(), { defaultLighting: 'studio' as 'neutral' }), (e) => isGpuRendererError(e) && e.code === 'INVALID_OPTION' && e.field === 'defaultLighting');
});

test('the CLI lights a glTF without lights by the neutral environment and says so; --env none renders black', async () => {
  const dir = await mkdtemp(join(tmpdir(), 'gpu-renderer-default-light-'));
  try {
    const model = join(dir, 'quad.glb');
    await writeFile(model, await new NodeIO().registerExtensions(ALL_EXTENSIONS).writeBinary(quadDocument()));
    const args = ['--width', '16', '--height', '16', '--spp', '2', '--max-depth', '2'];
    const lit = await run(['render', model, ...args, '--out', join(dir, 'lit.png')]);
    assert.equal(lit.code, 0, lit.stderr);
    assert.ok(lit.stderr.includes(`\n  ${NEUTRAL_LIGHTING_SUMMARY}\n`), lit.stderr);
    const litPng = decode(await readFile(join(dir, 'lit.png')));
    let bright = 0;
    for (let i = 0; i < litPng.data.length; i += 4) if (litPng.data[i]! > 0) bright++;
    assert.equal(bright, 16 * 16, 'every pixel (quad and background) is lit');

    const dark = await run(['render', model, ...args, '--env', 'none', '--out', join(dir, 'dark.png')]);
    assert.equal(dark.code, 0, dark.stderr);
    assert.match(dark.stderr, /\n {2}unlit: --env none and the scene has no light of its own \(the image is black\)\n/);
    const darkPng = decode(await readFile(join(dir, 'dark.png')));
    for (let i = 0; i < darkPng.data.length; i += 4) assert.deepEqual([...darkPng.data.subarray(i, i + 3)], [0, 0, 0], `pixel ${i / 4}`);
  } finally {
    await rm(dir, { recursive: true, force: true });
  }
});
