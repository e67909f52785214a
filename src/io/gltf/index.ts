export { loadGltfScene, type GltfScene, type GltfLoadOptions, type GltfPoseOptions, type GltfPoseAgainOptions, type GltfAnimationInfo, type GltfSource, type GltfDecoderModules, type GltfBounds, type GltfCameraInfo } from './load-gltf-scene.ts';
export { resolveGltfReferences } from './scene-file-references.ts';
