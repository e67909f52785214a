// Asset input: scene formats other than the renderer's own JSON.
export * from './gltf/index.ts';
export { loadSceneFile, resolveSceneFile, type ResolvedSceneFile } from './scene-file-loader.ts';
