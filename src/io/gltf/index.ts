export { loadGltfScene, type GltfScene, type GltfLoadOptions, type GltfSource, type GltfDecoderModules, type GltfBounds, type GltfCameraInfo } from './load-gltf-scene.ts';
export { parseGltfReferences, resolveGltfReferences, type GltfSceneReference } from './scene-file-references.ts';
