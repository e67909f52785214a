import type { WavefrontRadianceImage } from '../film/accumulation/readback.ts';
export type { WavefrontRadianceImage } from '../film/accumulation/readback.ts';
import type { WavefrontLightingOptions, WavefrontSceneLightInput } from '../lighting/lighting-options.ts';
import type { WavefrontAovName } from '../film/aovs.ts';
import type { WavefrontCameraInput, WavefrontSceneDescription, WavefrontToneMapping } from '../scene/types.ts';
import type { WavefrontOutputOptions, WavefrontRenderFrameOptions } from './output-options.ts';
import type { AccelerationBuildMode } from './scene/prepare-scene.ts';
import type { InstancingMode, WavefrontInstancingStats } from './scene/instancing.ts';

export type { WavefrontInstancingStats } from './scene/instancing.ts';
import type { WavefrontGeometryUpdate, WavefrontGeometryUpdateStats } from './scene/geometry-update.ts';
import type {
  WavefrontAdaptiveFrameStats,
  WavefrontGpuParallelism,
  WavefrontOutputState,
  WavefrontRadianceDiagnostics,
  WavefrontTerminalRadiance,
  WavefrontTransportGuardrails,
} from './output-types.ts';

export type { WavefrontOutputOptions, WavefrontRenderFrameOptions } from './output-options.ts';
export type * from './output-types.ts';
export type { WavefrontFeatureFlagState, WavefrontTransportExperimentState, WavefrontFeatureFlagResolution, TransportExperimentName } from './feature-flags.ts';

export type { AccelerationBuildMode } from './scene/prepare-scene.ts';
export type { WavefrontGeometryUpdate, WavefrontGeometryUpdateStats, WavefrontMeshGeometryUpdate, WavefrontInstanceTransformUpdate } from './scene/geometry-update.ts';
export type { BvhUpdateMode } from './scene/scene-acceleration.ts';

import type { CanvasTarget } from '../film/display/canvas-target.ts';
export type { CanvasTarget } from '../film/display/canvas-target.ts';

/** What `updateScene` replaces; what is left out stays. */
export interface WavefrontSceneUpdate {
  meshes?: WavefrontSceneDescription['meshes'];
  /** Without `instances`, the current instances place the new meshes. */
  instances?: WavefrontSceneDescription['instances'];
  lights?: WavefrontSceneLightInput[];
  camera?: WavefrontCameraInput;
}

/**
 * Renderer options: the scene (what a scene file or the glTF loader gives) plus render settings and
 * the lighting options (environment map or sky, portals, light sampler) and the output options
 * (adaptive sampling, denoising, presentation, feature flags; output-options.ts).
 */
/** The path tracer's integrator form (WavefrontPathTracingOptions.integrator). */
export type PathTracingIntegrator = 'wavefront' | 'megakernel';

export interface WavefrontPathTracingOptions extends Omit<WavefrontSceneDescription, 'lights'>, WavefrontLightingOptions, WavefrontOutputOptions {
  /** KHR_lights_punctual point, spot and directional lights, and rectangle, disk and sphere area lights. */
  lights?: WavefrontSceneLightInput[];
  width: number;
  height: number;
  /** Scattering events per path (pbrt-v4 semantics), 1..32; default 8. */
  maxDepth?: number;
  /** Samples per pixel added by each renderFrame call; default 1. */
  samplesPerPixel?: number;
  /**
   * Bounds the paths of one wave to tileSize^2 (8..1024), and with it the queue memory. By default a
   * wave holds as many paths as the frame has (pixels x samples) up to what the device binds and
   * 2^21 paths (wave-capacity.ts).
   */
  tileSize?: number;
  /**
   * How a wave's paths run (default 'wavefront'): 'wavefront' runs each bounce of all paths as a
   * traversal and a shading dispatch over queues; 'megakernel' runs each path through all its
   * bounces in one invocation of one kernel. Both compute the same samples; which is faster depends
   * on the GPU and the scene (`npm run bench` measures both).
   */
  integrator?: PathTracingIntegrator;
  /**
   * Frames renderFrame may have submitted before their statistics come back (1..4, default 2): a
   * call that does not await the previous one's result submits at once unless this many frames are
   * still in flight. 1 submits a frame only after the previous frame's statistics were read.
   */
  framesInFlight?: number;
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
  /**
   * Accumulate the AOVs of each sample's first non-specular hit (albedo, normal, depth, object and
   * material id) and the film moments (variance) for readAov. Default false.
   */
  aovs?: boolean;
  /**
   * Multiple-scattering energy compensation of rough microfacet lobes (Turquin 2019 for conductors
   * and rough transmission; Kulla and Conty 2017 albedo scaling for the diffuse lobes under the
   * dielectric specular layer). Single-scattering microfacet models lose the energy of light that
   * bounces more than once between microfacets (rough metals and rough glass darken); with
   * compensation a rough white furnace stays close to 1 (never above). Default true; false gives
   * the glTF 2.0 Appendix B model as specified, whose 1 - F(wo.h) layering also gains up to about 3%
   * at grazing angles on rough dielectrics.
   */
  energyCompensation?: boolean;
  /**
   * Where the BVH is built. 'cpu-upload' (default): top-down binned SAH on the CPU (worker threads
   * for large meshes), uploaded once. 'gpu': an LBVH built by WGSL compute passes on the device
   * (Morton codes, radix sort, Karras 2012 hierarchy, SAH leaf collapse), for a real GPU where
   * building dominates; its tree's SAH cost is about 25-30 % above the CPU build's (README,
   * Performance). Both are traced by the same kernels and render the same image.
   */
  accelerationBuildMode?: AccelerationBuildMode;
  /**
   * Two-level acceleration for meshes placed many times (reused glTF nodes, EXT_mesh_gpu_instancing,
   * `instances`): each such mesh is stored and built once, in object space, and each placement is
   * one record of the top-level tree, so memory and build time follow unique geometry. 'auto'
   * (default): meshes placed more than once whose copies would add at least 1,024 triangles;
   * 'always': every placement; 'off': every placement flattened into world-space triangles.
   * All three render the same image.
   */
  instancing?: InstancingMode;
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
  /** Wave-sized buffers: the path records and the queues (with the statistics). */
  queueBytes: number;
  /** Full-frame float32 accumulation (and AOVs) plus the display buffer. */
  frameBytes: number;
  totalBytes: number;
}

export interface WavefrontFrameStats {
  /** Frames rendered since the accumulation last restarted. */
  frame: number;
  /** Samples per pixel added by this call (sample passes; adaptive sampling skips converged pixels). */
  samplesAdded: number;
  /** Samples per pixel in the accumulation (the most any pixel holds with adaptive sampling). */
  samplesAccumulated: number;
  /** The call's samplesPerPixel: a ceiling when frameTimeBudgetMs or adaptive sampling ends the frame sooner. */
  samplesPerPixel: number;
  /** Sample passes actually rendered (equal to samplesAdded; the 0.2 API's name, kept for its hosts). */
  renderedSamplesPerPixel: number;
  frameTimeBudgetMs: number | null;
  rays: WavefrontRayCounts;
  /**
   * How paths ended: Russian roulette, reaching maxDepth, escaping to the environment, zero
   * throughput (absorbed), or a BSDF sample with no valid direction.
   */
  terminations: { russianRoulette: number; maxDepth: number; escaped: number; absorbed: number; invalidBsdfSample: number; invalidThroughput: number };
  /** Samples that lost a contribution as NaN/Inf or negative (dropped and counted, never clamped). */
  invalidSamples: number;
  radianceDiagnostics: WavefrontRadianceDiagnostics;
  terminalRadiance: WavefrontTerminalRadiance;
  /** Rays whose BVH traversal overflowed its stack and finished in stackless mode (exact, slower). */
  traversalFallbacks: number;
  /** GPU time of this frame in ms where timestamp queries exist, else null. */
  gpuTimeMs: number | null;
  /** Wall-clock time of renderFrame in ms. */
  wallTimeMs: number;
  memory: WavefrontMemoryStats;
  /** Waves one sample of every pixel takes (ceil(pixels / wavePaths)). */
  tiles: number;
  waves: number;
  /** Paths per wave: the queue capacity this frame ran with. */
  wavePaths: number;
  /** Adaptive sampling's state after the frame; null when it is off. */
  adaptive: WavefrontAdaptiveFrameStats | null;
  /** Whether the denoiser ran in this frame (it runs when the canvas shows the denoised image, else on read). */
  denoised: boolean;
  gpuParallelism: WavefrontGpuParallelism;
  transportGuardrails: WavefrontTransportGuardrails;
  maxFramePassesPerSubmission: number;
  presentationOutput: WavefrontOutputState['presentationOutput'];
  exposureEv: number;
  adaptiveSampling: WavefrontOutputState['adaptiveSampling'];
  denoise: WavefrontOutputState['denoise'];
  featureFlags: WavefrontOutputState['featureFlags'];
  transportExperiments: WavefrontOutputState['transportExperiments'];
  transportExperimentFlags: number;
  transportExperimentRequestedFlags: number;
}


export interface WavefrontPixelImage {
  width: number;
  height: number;
  /** Tone-mapped sRGB RGBA8, row-major, top row first. */
  data: Uint8ClampedArray;
}

export interface WavefrontRendererSnapshot extends WavefrontOutputState {
  width: number;
  height: number;
  frame: number;
  samplesAccumulated: number;
  maxDepth: number;
  samplesPerPixel: number;
  /** The explicit wave bound (tileSize^2 paths), or null when waves are sized to the device. */
  tileSize: number | null;
  /**
   * The integrator form that runs: the one requested, except that 'megakernel' on a device with
   * fewer storage buffers per shader stage than it binds runs 'wavefront' (the same image), with a
   * line in `warnings` saying so.
   */
  integrator: PathTracingIntegrator;
  /** The integrator form the options asked for (`integrator`, default 'wavefront'). */
  requestedIntegrator: PathTracingIntegrator;
  /** Paths per wave the queues now hold (they grow up to the bound as frames need). */
  wavePaths: number;
  /** Most paths a wave may hold on this device (or tileSize^2). */
  maxWavePaths: number;
  framesInFlight: number;
  /** Triangles over all placements (as if every placement were flattened). */
  triangleCount: number;
  /** Nodes of the top-level tree and every bottom level. */
  bvhNodeCount: number;
  /** How placements are traced: shared meshes with bottom-level trees, and what they store. */
  instancing: WavefrontInstancingStats;
  lightCount: number;
  sceneObjectCount: number;
  instanceCount: number;
  textureCount: number;
  /** Edges from the top-level root to the deepest leaf, through a bottom level where placements lead. */
  bvhDepth: number;
  /** Loader, preparation and device warnings (downscaled textures, an integrator the device cannot run, ...). */
  warnings: readonly string[];
  adapter: string;
  memory: WavefrontMemoryStats;
  destroyed: boolean;
  deviceLost: boolean;
  /** Adaptive sampling: pixels still sampling and mean samples per pixel; null when off. */
  adaptive: { activePixels: number; meanSamplesPerPixel: number } | null;
  /** The adapter's compute limits and workgroup size (the per-frame dispatch counts are in frame stats). */
  gpuParallelism: Pick<WavefrontGpuParallelism, 'adapterLimits' | 'workgroupSize' | 'physicalCoreCount'>;
}

/**
 * The path tracer. It is an EventTarget: `addEventListener('progress', (e) => e.detail)` receives
 * WavefrontRenderProgress events (as does the `onProgress` option).
 */
export interface WavefrontPathTracingRenderer extends EventTarget {
  /**
   * Renders and accumulates samplesPerPixel more samples (a ceiling with frameTimeBudgetMs or
   * adaptive sampling) and resolves to the frame's statistics.
   */
  renderFrame(options?: WavefrontRenderFrameOptions): Promise<WavefrontFrameStats>;
  /** Submits one frame's work without waiting for it (no frameTimeBudgetMs). */
  renderOnce(options?: WavefrontRenderFrameOptions): void;
  updateCamera(camera: WavefrontCameraInput): void;
  /**
   * Moves the scene's geometry without recreating the renderer (the next pose of an animation):
   * new positions (normals, tangents) of its meshes and new instance transforms, topology kept.
   * The BVH is refitted on the GPU (default) or rebuilt (`bvh: 'rebuild'`), the light tables
   * follow, and the accumulation restarts. Validated before anything changes: a refused update
   * (typed error naming the field) leaves the renderer as it was.
   */
  updateGeometry(update: WavefrontGeometryUpdate): Promise<WavefrontGeometryUpdateStats>;
  /**
   * Replaces the scene's meshes, instances and/or lights, and the camera (what `updateGeometry`
   * cannot: other meshes or triangle counts, other mesh materials, instances added or removed,
   * moved punctual lights) without recreating the renderer: materials, textures, the environment
   * and the compiled kernels stay; the geometry buffers are rewritten (reallocated only when they
   * must grow), the BVH is built anew in the renderer's accelerationBuildMode, and the
   * accumulation restarts. Validation errors name the field as at creation. A change that needs a
   * shader feature the kernels were specialised without (the first alpha-tested or emissive
   * surface, the first punctual light) is an INVALID_STATE error, and the renderer is left as it
   * was: create a new one, or one with `shaderSpecialization: 'off'`.
   */
  updateScene(update: WavefrontSceneUpdate): Promise<void>;
  /** The raw linear mean radiance, RGBA float32 (alpha 1), top row first: never denoised. */
  readRadiance(): Promise<WavefrontRadianceImage>;
  /** The denoised linear radiance of the accumulation (needs `denoise`), RGBA float32 (alpha 1). */
  readDenoised(): Promise<WavefrontRadianceImage>;
  /**
   * An AOV, RGBA float32, top row first (all but sampleCount need `aovs: true`):
   * 'albedo' (rgb), 'normal' (world shading normal xyz), 'depth' (distance from the eye, in r) and
   * 'emission' (rgb: emitted radiance reaching the eye from the first non-specular hit) are means
   * over the samples with alpha = coverage (the share of samples that reached a non-specular
   * surface; the others contribute zeros); 'objectId' and 'materialId' (r; -1 where no sample
   * reached a surface) come from the pixel's first sample that did; 'variance' is the variance of
   * the mean radiance per channel (rgb) and of the mean luminance of the radiance without the
   * emission (alpha: the noise the denoiser filters), +Infinity below two samples;
   * 'sampleCount' (r) the samples the pixel received, with adaptive sampling also the error of the
   * last convergence test (g; 3.4e38 below the minimum samples) and whether the pixel still samples (b).
   */
  readAov(name: WavefrontAovName): Promise<WavefrontRadianceImage>;
  /** What the canvas shows: tone-mapped (or linear) RGBA8 of the raw or denoised image. */
  readPixels(): Promise<WavefrontPixelImage>;
  getSnapshot(): WavefrontRendererSnapshot;
  destroy(): void;
  readonly device: GPUDevice;
}
