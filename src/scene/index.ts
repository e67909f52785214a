export type * from './types.ts';
export { normalizeWavefrontMesh, type NormalizedMesh } from './mesh.ts';
export { normalizeMaterial, defaultMaterial, type NormalizedMaterial } from './material.ts';
export { normalizeWavefrontSceneObject, packWavefrontSceneObjects, type NormalizedSceneObject } from './scene-object.ts';
export { createWavefrontGpuMeshSource, type WavefrontGpuMeshSource } from './gpu-mesh-source.ts';
export { packWavefrontMaterials } from './material-packing.ts';
export { createCornellBoxScene } from './cornell-box.ts';
export { parseSceneFile, validateSceneDescription } from './scene-file.ts';
