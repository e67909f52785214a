import type { WavefrontLightingOptions, WavefrontSceneLightInput } from '../lighting/lighting-options.ts';
import type { WavefrontCameraInput, WavefrontSceneDescription, WavefrontToneMapping } from '../scene/types.ts';

export type CanvasTarget = HTMLCanvasElement | OffscreenCanvas | string;

/**
 * Renderer options: the scene (what a scene file or the glTF loader gives) plus render settings and
 * the lighting options (environment map or sky, portals, light sampler).
 */
export interface WavefrontPathTracingOptions extends Omit<WavefrontSceneDescription, 'lights'>, WavefrontLightingOptions {
  /** KHR_lights_punctual point, spot and directional lights, and rectangle, disk and sphere area lights. */
  lights?: WavefrontSceneLightInput[];
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
  /** Tone mapping for readPixels and the canvas; default 'neutral' (Khronos PBR Neutral). */
  toneMapping?: WavefrontToneMapping;
  /** Exposure multiplier applied before tone mapping; default 1. */
  exposure?: number;
  /**
   * Kernel specialisation: 'scene' (default) compiles every optional shader feature the scene does
   * not use out of the kernels (override constants); 'off' compiles them all in. The image is the
   * same either way; 'off' exists to check exactly that.
   */
  shaderSpecialization?: 'scene' | 'off';
  /** Accumulate albedo, normal and depth of each sample's first non-specular hit (readAov). Default false. */
  aovs?: boolean;
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
  /** Scene buffers: primitives, BVH, instances, vertex streams, materials, lights. */
  sceneBytes: number;
  /** The material texture atlas (included in sceneBytes). */
  textureBytes: number;
  /** Tile-sized queues: paths, rays, hits, surfaces, shadow rays, samples, counters. */
  queueBytes: number;
  /** Full-frame float32 accumulation (and AOVs) plus the display buffer. */
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
  /**
   * How paths ended: Russian roulette, reaching maxDepth, escaping to the environment, zero
   * throughput (absorbed), or a BSDF sample with no valid direction.
   */
  terminations: { russianRoulette: number; maxDepth: number; escaped: number; absorbed: number; invalidBsdfSample: number };
  /** Samples that produced NaN/Inf or negative radiance (dropped and counted, never clamped). */
  invalidSamples: number;
  /** Rays whose BVH traversal overflowed its stack and finished in stackless mode (exact, slower). */
  traversalFallbacks: number;
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
  instanceCount: number;
  textureCount: number;
  bvhDepth: number;
  /** Loader and preparation warnings (downscaled textures, ...). */
  warnings: readonly string[];
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
  /**
   * Mean of an AOV over the accumulated samples (needs `aovs: true`): 'albedo' (rgb), 'normal'
   * (world shading normal xyz) or 'depth' (distance from the camera, in r); RGBA float32, top row
   * first. Samples whose path never reached a non-specular surface contribute zeros.
   */
  readAov(name: 'albedo' | 'normal' | 'depth'): Promise<WavefrontRadianceImage>;
  readPixels(): Promise<WavefrontPixelImage>;
  getSnapshot(): WavefrontRendererSnapshot;
  destroy(): void;
  readonly device: GPUDevice;
}
