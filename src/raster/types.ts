import type { EnvironmentLightingInput } from '../lighting/environment-lighting.ts';
import type { EnvironmentMapInput } from '../lighting/environment-map.ts';
import type { GpuRendererCanvas, GpuRendererFormat, RendererPixels } from '../runtime/renderer-types.ts';
import type {
  WavefrontCameraInput,
  WavefrontImageInput,
  WavefrontInstanceInput,
  WavefrontMaterialInput,
  WavefrontMeshInput,
  WavefrontPunctualLightInput,
  WavefrontTextureInput,
  WavefrontToneMapping,
} from '../scene/types.ts';

/**
 * A deformable mesh: bind-pose vertex streams (model space) deformed on the GPU every frame by
 * morph targets and, with `influences` 4 or 8, linear blend skinning (glTF 2.0 sections 3.7.2.2
 * and 3.7.3). `influences: 0` is a morph-only mesh.
 */
export interface RasterSkinnedMeshInput extends Omit<WavefrontMeshInput, 'emission'> {
  /** Joints per vertex: 0 (morph only), 4 (JOINTS_0) or 8 (JOINTS_0 + JOINTS_1). */
  influences: 0 | 4 | 8;
  /** `influences` joint indices per vertex, into the skin's joint palette. */
  joints?: ArrayLike<number>;
  /** `influences` weights per vertex (normalised here when they do not sum to 1). */
  weights?: ArrayLike<number>;
  /** Size of the joint palette (`setSkinPose` uploads this many matrices). */
  jointCount?: number;
  /** Morph target deltas (xyz per vertex each). */
  targets?: readonly { positions?: ArrayLike<number>; normals?: ArrayLike<number>; tangents?: ArrayLike<number> }[];
}

/** A placement of a skinned mesh: it has its own pose (joint palette and morph weights). */
export interface RasterSkinnedInstanceInput {
  /** Index into `skinnedMeshes`. */
  mesh: number;
  /** Model -> world, column-major 4x4; default identity. */
  transform?: ArrayLike<number>;
}

/** Which light casts the shadow map, and its resolution. */
export interface RasterShadowOptions {
  /** Index into `lights` of a directional or spot light; default the sun, else the first directional light. */
  light?: number;
  /** Shadow map edge in texels; default 2048. */
  mapSize?: number;
  /** Depth bias in the light's normalised depth; default 0.002. */
  bias?: number;
}

export interface RasterRendererOptions {
  width: number;
  height: number;
  camera?: WavefrontCameraInput;
  meshes?: WavefrontMeshInput[];
  instances?: WavefrontInstanceInput[];
  materials?: WavefrontMaterialInput[];
  textures?: WavefrontTextureInput[];
  images?: WavefrontImageInput[];
  lights?: WavefrontPunctualLightInput[];
  skinnedMeshes?: RasterSkinnedMeshInput[];
  skinnedInstances?: RasterSkinnedInstanceInput[];
  /** Uniform environment radiance (the scene format's `environment`). */
  environment?: { color: readonly number[] };
  /** An equirect radiance map; prefiltered on the GPU at load. */
  environmentMap?: EnvironmentMapInput;
  /** A procedural sky (src/lighting): its map lights the scene, its sun becomes the shadowed key light. */
  environmentLighting?: EnvironmentLightingInput;
  /** Default 'neutral' (the path tracer's default). */
  toneMapping?: WavefrontToneMapping;
  /** Default 1. */
  exposure?: number;
  /** Samples per pixel of the multisampled target: 1 or 4 (default). */
  msaa?: 1 | 4;
  /** false turns shadows off. */
  shadow?: RasterShadowOptions | false;
  canvas?: GpuRendererCanvas;
  /** Output format; default the canvas's preferred format, rgba8unorm offscreen. */
  format?: GpuRendererFormat;
  device?: GPUDevice;
  powerPreference?: GPUPowerPreference;
}

export interface RasterFrameStats {
  readonly frame: number;
  /** Wall time from encoding to the queue reporting the frame done. */
  readonly frameTimeMs: number;
  readonly drawCalls: number;
  readonly triangles: number;
  readonly skinnedVertices: number;
}

export interface RasterCameraState {
  position: readonly number[];
  target: readonly number[];
  up?: readonly number[];
  fovYDegrees?: number;
}

export interface RasterRenderer {
  readonly device: GPUDevice;
  readonly format: GpuRendererFormat;
  readonly width: number;
  readonly height: number;
  setCamera(camera: WavefrontCameraInput): void;
  /** Places instance `index` (of `instances`) with a new column-major transform. */
  setInstanceTransform(index: number, transform: ArrayLike<number>): void;
  /** Places skinned instance `index`. */
  setSkinnedInstanceTransform(index: number, transform: ArrayLike<number>): void;
  /** The pose of skinned instance `index`: joint matrices (16 floats each) and morph weights. */
  setSkinPose(index: number, jointMatrices: ArrayLike<number>, morphWeights?: ArrayLike<number>): void;
  /** Draws hidden (false) or shown instances. */
  setInstanceVisible(index: number, visible: boolean): void;
  /** Centre and radius of what the directional shadow map must cover; default the scene bounds. */
  setShadowFocus(center: readonly number[], radius: number): void;
  resize(width: number, height: number): void;
  render(): Promise<RasterFrameStats>;
  /** The output (tone-mapped, sRGB) as RGBA8; offscreen targets only. */
  readPixels(): Promise<RendererPixels>;
  /** The skinned instance's deformed vertices as the GPU wrote them (model space). */
  readSkinnedVertices(index: number): Promise<{ positions: Float32Array; normals: Float32Array | null; tangents: Float32Array | null }>;
  destroy(): void;
}
