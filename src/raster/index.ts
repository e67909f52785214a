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
