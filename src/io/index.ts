// Asset input: scene formats other than the renderer's own JSON.
export * from './gltf/index.ts';
