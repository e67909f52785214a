import { test } from 'node:test';
import assert from 'node:assert/strict';
import { parseSceneFile, validateSceneDescription } from '../../src/scene/scene-file.ts';
import { createCornellBoxScene } from '../../src/scene/cornell-box.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';

const valid = {
  camera: { position: [0, 1, 5], target: [0, 0, 0], up: [0, 1, 0], fovYDegrees: 40 },
  environment: { color: [0.1, 0.2, 0.3] },
  meshes: [
    {
      id: 'tri',
      positions: [0, 0, 0, 1, 0, 0, 0, 1, 0],
      indices: [0, 1, 2],
      normals: [0, 0, 1, 0, 0, 1, 0, 0, 1],
      uvs: [0, 0, 1, 0, 0, 1],
      material: { baseColorFactor: [1, 0.5, 0.25, 1], metallicFactor: 0, roughnessFactor: 0.5, emissiveFactor: [1, 1, 1], emissiveStrength: 3, ior: 1.5, doubleSided: true },
    },
    { id: 7, positions: [0, 0, 0, 1, 0, 0, 0, 1, 0], emission: [1, 1, 1, 10] },
  ],
  sceneObjects: [
    { type: 'sphere', center: [0, 1, 0], radius: 0.5, color: [0.8, 0.8, 0.8], roughness: 0.2, metallic: 1, ior: 1.5, materialKind: 'metal' },
    { type: 'box', min: [-1, -1, -1], max: [1, -0.9, 1], emission: [1, 1, 1, 2] },
  ],
};

function expectError(text: string, field: string | undefined, message?: RegExp): void {
  assert.throws(
    () => parseSceneFile(text, 'scene.json'),
    (e: unknown) => {
      assert.ok(e instanceof GpuRendererError, String(e));
      assert.equal(e.code, 'INVALID_SCENE_FILE');
      assert.equal(e.field, field);
      assert.match(e.message, /\(in scene\.json\)$/);
      if (message) assert.match(e.message, message);
      return true;
    },
  );
}

/** The valid scene with one change made by `edit`. */
// eslint-disable-next-line @typescript-eslint/no-explicit-any -- tests poke arbitrary (invalid) shapes into the copy
function edited(edit: (scene: any) => void): string {
  const copy = structuredClone(valid);
  edit(copy);
  return JSON.stringify(copy);
}

test('parses a complete scene file and keeps every value', () => {
  assert.deepEqual(parseSceneFile(JSON.stringify(valid)), valid);
  assert.deepEqual(parseSceneFile('{}'), {});
});

test('the built-in Cornell box round-trips through JSON', () => {
  const scene = createCornellBoxScene();
  assert.deepEqual(parseSceneFile(JSON.stringify(scene)), JSON.parse(JSON.stringify(scene)));
  assert.deepEqual(validateSceneDescription(scene), scene);
});

test('rejects invalid JSON and non-object roots', () => {
  expectError('{"camera": ', undefined, /not valid JSON/);
  expectError('[]', undefined, /JSON object/);
  expectError('null', undefined, /JSON object/);
});

test('rejects unknown keys at every level, naming the field path', () => {
  expectError(edited((s) => (s.skybox = [])), 'skybox', /unknown key "skybox"/);
  expectError(edited((s) => (s.camera.fov = 40)), 'camera.fov');
  expectError(edited((s) => (s.meshes[1].colour = [1, 1, 1])), 'meshes[1].colour');
  expectError(edited((s) => (s.meshes[0].material.roughness = 1)), 'meshes[0].material.roughness');
  expectError(edited((s) => (s.sceneObjects[0].size = 1)), 'sceneObjects[0].size');
  expectError(edited((s) => (s.environment.intensity = 1)), 'environment.intensity');
});

test('rejects wrong types, naming the field path', () => {
  expectError(edited((s) => (s.meshes = {})), 'meshes', /expected an array/);
  expectError(edited((s) => (s.meshes[1] = 3)), 'meshes[1]', /expected an object/);
  expectError(edited((s) => (s.meshes[1].positions = 'abc')), 'meshes[1].positions', /array of numbers/);
  expectError(edited((s) => (s.meshes[1].positions[4] = '1')), 'meshes[1].positions[4]', /finite number/);
  expectError(edited((s) => (s.meshes[0].indices[2] = null)), 'meshes[0].indices[2]');
  expectError(edited((s) => delete s.meshes[0].positions), 'meshes[0].positions', /required/);
  expectError(edited((s) => (s.meshes[0].id = true)), 'meshes[0].id', /string/);
  expectError(edited((s) => (s.meshes[0].material.doubleSided = 1)), 'meshes[0].material.doubleSided');
  expectError(edited((s) => (s.meshes[0].material.baseColorFactor = [1, 1])), 'meshes[0].material.baseColorFactor', /3 or 4 numbers/);
  expectError(edited((s) => (s.meshes[0].material.roughnessFactor = 2)), 'meshes[0].material.roughnessFactor', /<= 1/);
  expectError(edited((s) => (s.meshes[1].emission = [1, 1, 1])), 'meshes[1].emission', /4 numbers/);
  expectError(edited((s) => (s.camera.position = [0, 0])), 'camera.position');
  expectError(edited((s) => delete s.camera.target), 'camera.target', /required/);
  expectError(edited((s) => (s.camera.fovYDegrees = 0)), 'camera.fovYDegrees', /> 0/);
  expectError(edited((s) => (s.environment = { color: [1, 1, 'x'] })), 'environment.color[2]');
  expectError(edited((s) => (s.sceneObjects[1].type = 'cone')), 'sceneObjects[1].type', /"sphere" or "box"/);
  expectError(edited((s) => (s.sceneObjects[0].radius = -1)), 'sceneObjects[0].radius');
  // JSON has no Infinity, but 1e999 parses to it.
  expectError('{"meshes":[{"positions":[0,0,1e999]}]}', 'meshes[0].positions[2]', /finite/);
});

test('errors without a path do not mention one', () => {
  assert.throws(
    () => parseSceneFile('{"x":1}'),
    (e: unknown) => e instanceof GpuRendererError && e.message === 'x: unknown key "x" (expected one of camera, environment, meshes, instances, materials, textures, images, sceneObjects, lights, gltf)',
  );
});
