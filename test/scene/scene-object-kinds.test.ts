// Scene objects' `materialKind`: the debug material the object is, checked against its fields (a
// typed error naming the field where they disagree or the kind is unknown) and setting the metallic
// factor they leave open; the scene JSON reader refuses unknown kinds naming the field.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { normalizeWavefrontSceneObject } from '../../src/scene/scene-object.ts';
import { parseSceneFile } from '../../src/scene/scene-file.ts';
import { isGpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import type { WavefrontSceneObjectInput } from '../../src/scene/types.ts';

const sphere = { type: 'sphere', center: [0, 0, 0], radius: 1 } as const;

function refused(input: object, field: string, message: RegExp): void {
  assert.throws(() => normalizeWavefrontSceneObject(input as WavefrontSceneObjectInput, 2), (e) => isGpuRendererError(e) && e.code === 'INVALID_SCENE_OBJECT' && e.field === field && message.test(e.message));
}

test("materialKind 'metal' makes a conductor, 'diffuse' a dielectric base; a contradicting metallic is refused", () => {
  assert.equal(normalizeWavefrontSceneObject({ ...sphere, materialKind: 'metal' }).material.metallic, 1);
  assert.equal(normalizeWavefrontSceneObject({ ...sphere, materialKind: 'metal', metallic: 1, roughness: 0.2 }).material.roughness, 0.2);
  assert.equal(normalizeWavefrontSceneObject({ ...sphere, materialKind: 'diffuse' }).material.metallic, 0);
  assert.equal(normalizeWavefrontSceneObject({ ...sphere, metallic: 0.4 }).material.metallic, 0.4, 'without a kind the field is free');
  refused({ ...sphere, materialKind: 'diffuse', metallic: 1 }, 'sceneObjects[2].metallic', /materialKind 'diffuse' means metallic 0/);
  refused({ ...sphere, materialKind: 'metal', metallic: 0.5 }, 'sceneObjects[2].metallic', /materialKind 'metal' means metallic 1/);
});

test("materialKind 'emissive' needs emission; an unknown kind is refused naming materialKind", () => {
  const lamp = normalizeWavefrontSceneObject({ ...sphere, materialKind: 'emissive', emission: [8, 7, 5, 1] });
  assert.deepEqual(lamp.material.emission, [8, 7, 5]);
  refused({ ...sphere, materialKind: 'emissive' }, 'sceneObjects[2].emission', /needs emission with radiance > 0/);
  refused({ ...sphere, materialKind: 'emissive', emission: [1, 1, 1, 0] }, 'sceneObjects[2].emission', /needs emission/);
  refused({ ...sphere, materialKind: 'glass' }, 'sceneObjects[2].materialKind', /expected one of diffuse, metal, emissive, got "glass"/);
  assert.throws(
    () => parseSceneFile(JSON.stringify({ sceneObjects: [{ ...sphere }, { ...sphere, materialKind: 'plastic' }] }), 'scene.json'),
    (e) => isGpuRendererError(e) && e.code === 'INVALID_SCENE_FILE' && e.field === 'sceneObjects[1].materialKind' && /expected one of diffuse, metal, emissive/.test(e.message),
  );
});
