// Asset input: scene formats other than the renderer's own JSON.
export * from './gltf/index.ts';
export { loadSceneFile, resolveSceneFile, type ResolvedSceneFile, type ResolveSceneFileOptions, type WavefrontResolvedScene } from './scene-file-loader.ts';
export { defaultResourcePolicy, resolveResourcePolicy, type ResourcePolicy, type ResolvedResourcePolicy } from './resource-policy.ts';
export * from './images/index.ts';
