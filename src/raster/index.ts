// Forward WebGPU raster renderer of the shared scene (glTF PBR with IBL, shadows, MSAA, GPU skinning).
export { createRasterRenderer } from './renderer.ts';
export type {
  RasterRenderer,
  RasterRendererOptions,
  RasterFrameStats,
  RasterSkinnedMeshInput,
  RasterSkinnedInstanceInput,
  RasterShadowOptions,
  RasterCameraState,
} from './types.ts';
export { createAnimatedSceneRenderer } from './animated/animated-scene-renderer.ts';
export { createProfessionalAnimatedSceneRenderer } from './animated/professional-renderer.ts';
export { builtInPropKinds } from './animated/prop-meshes.ts';
export type { AnimatedPosedScene, AnimatedSceneRenderer, AnimatedSceneRendererOptions, AnimatedSceneSnapshot } from './animated/animated-types.ts';
