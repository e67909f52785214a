import type {
  WavefrontCameraInput,
  WavefrontEnvironmentInput,
  WavefrontMeshInput,
  WavefrontSceneObjectInput,
  WavefrontToneMapping,
} from '../scene/types.ts';

export type CanvasTarget = HTMLCanvasElement | OffscreenCanvas | string;

export interface WavefrontPathTracingOptions {
  width: number;
  height: number;
  /** Scattering events per path (pbrt-v4 semantics), 1..32; default 8. */
  maxDepth?: number;
  /** Samples per pixel added by each renderFrame call; default 1. */
  samplesPerPixel?: number;
  /** Edge of the square tile a wave covers; the queues hold tileSize^2 paths. Default 256. */
  tileSize?: number;
  /** Sampler seed; the same seed gives the same image. Default 0. */
  seed?: number;
  camera?: WavefrontCameraInput;
  meshes?: WavefrontMeshInput[];
  sceneObjects?: WavefrontSceneObjectInput[];
  /** Uniform environment radiance; omitted means black. */
  environment?: WavefrontEnvironmentInput;
  /** Tone mapping for readPixels and the canvas; default 'neutral' (Khronos PBR Neutral). */
  toneMapping?: WavefrontToneMapping;
  /** Exposure multiplier applied before tone mapping; default 1. */
  exposure?: number;
  canvas?: CanvasTarget;
  /** Share a device; otherwise one is acquired (Dawn in Node.js). */
  device?: GPUDevice;
  powerPreference?: GPUPowerPreference;
}

export interface WavefrontRayCounts {
  camera: number;
  extension: number;
  shadow: number;
  total: number;
}

export interface WavefrontMemoryStats {
  /** Scene buffers: triangles, attributes, BVH, materials, objects, lights. */
  sceneBytes: number;
  /** Tile-sized queues: paths, shadow rays, tile radiance, counters. */
  queueBytes: number;
  /** Full-frame float32 accumulation plus the display buffer. */
  frameBytes: number;
  totalBytes: number;
}

export interface WavefrontFrameStats {
  /** Frames rendered since the accumulation last restarted. */
  frame: number;
  /** Samples per pixel added by this call. */
  samplesAdded: number;
  /** Samples per pixel in the accumulation. */
  samplesAccumulated: number;
  rays: WavefrontRayCounts;
  /** Paths ended by Russian roulette, by reaching maxDepth, by escaping. */
  terminations: { russianRoulette: number; maxDepth: number; escaped: number };
  /** Samples that produced NaN/Inf or negative radiance (dropped and counted, never clamped). */
  invalidSamples: number;
  /** GPU time of this frame in ms where timestamp queries exist, else null. */
  gpuTimeMs: number | null;
  /** Wall-clock time of renderFrame in ms. */
  wallTimeMs: number;
  memory: WavefrontMemoryStats;
  tiles: number;
  waves: number;
}

export interface WavefrontRadianceImage {
  width: number;
  height: number;
  /** RGBA, linear mean radiance, row-major, top row first. */
  data: Float32Array;
}

export interface WavefrontPixelImage {
  width: number;
  height: number;
  /** Tone-mapped sRGB RGBA8, row-major, top row first. */
  data: Uint8ClampedArray;
}

export interface WavefrontRendererSnapshot {
  width: number;
  height: number;
  frame: number;
  samplesAccumulated: number;
  maxDepth: number;
  samplesPerPixel: number;
  tileSize: number;
  triangleCount: number;
  bvhNodeCount: number;
  lightCount: number;
  sceneObjectCount: number;
  adapter: string;
  memory: WavefrontMemoryStats;
  destroyed: boolean;
  deviceLost: boolean;
}

export interface WavefrontRenderFrameOptions {
  /** Override samplesPerPixel for this call. */
  samplesPerPixel?: number;
}

export interface WavefrontPathTracingRenderer {
  renderFrame(options?: WavefrontRenderFrameOptions): Promise<WavefrontFrameStats>;
  /** Submits one frame's work without waiting for it. */
  renderOnce(options?: WavefrontRenderFrameOptions): void;
  updateCamera(camera: WavefrontCameraInput): void;
  readRadiance(): Promise<WavefrontRadianceImage>;
  readPixels(): Promise<WavefrontPixelImage>;
  getSnapshot(): WavefrontRendererSnapshot;
  destroy(): void;
  readonly device: GPUDevice;
}
