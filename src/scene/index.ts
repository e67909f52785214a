export type * from './types.ts';
export { normalizeWavefrontMesh, type NormalizedMesh } from './mesh.ts';
export { normalizeMaterial, normalizeTextureRef, defaultMaterial, type NormalizedMaterial, type NormalizedTextureRef } from './material.ts';
export { normalizeWavefrontSceneObject, type NormalizedSceneObject } from './scene-object.ts';
export { normalizeWavefrontInstance, type NormalizedInstance } from './instance.ts';
export { normalizeWavefrontScene, type NormalizedScene } from './normalize-scene.ts';
export { maxCoordinateMagnitude, maxRadiance, maxEmittedPower } from './limits.ts';
export { createCornellBoxScene } from './cornell-box.ts';
export { parseSceneFile, validateSceneDescription, type WavefrontSceneFile, type WavefrontEnvironmentMapReference } from './scene-file.ts';
