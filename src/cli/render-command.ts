/**
 * The `render` command: load a scene, path trace it in small increments with progress until the
 * sample ceiling, the time limit or the noise target, write a PNG, OpenEXR (with AOV layers) or
 * Radiance HDR image (atomically: a temporary file renamed). Sequences are sequence-command.ts.
 */
import { createWavefrontPathTracingComputeRenderer } from '../pathtracer/index.ts';
import type { WavefrontPathTracingRenderer } from '../pathtracer/types.ts';
import { GpuRendererError, isGpuRendererError } from '../errors/gpu-renderer-error.ts';
import { createCornellBoxScene } from '../scene/cornell-box.ts';
import type { WavefrontSceneDescription } from '../scene/types.ts';
import type { EnvironmentMapInput } from '../lighting/environment-map.ts';
import type { GltfScene } from '../io/gltf/gltf-scene-reader.ts';
import type { GltfAnimationInfo } from '../io/gltf/posing.ts';
import { applyCameraFlags } from './camera-flags.ts';
import { negativeTexelNote } from './environment-flags.ts';
import { applyCliLighting } from './scene-lighting.ts';
import { encodePng } from '../io/images/png.ts';
import { encodeImageFile } from '../io/images/image-file.ts';
import type { WavefrontAovName } from '../film/aovs.ts';
import { defaultAdaptiveSamplingParameters } from '../film/adaptive/converged-mask.ts';
import { writeFrameFile } from '../io/frame-files.ts';
import type { SequenceRendererOptions } from '../sequence/sequence-renderer.ts';
import { createProgressBar, type ProgressEstimate, type ProgressStream } from './progress.ts';
import { describeGeometry, type RenderSummary } from './render-format.ts';
import { isGltfPath, type RenderCommand } from './args.ts';
import type { ResourcePolicy } from '../io/resource-policy.ts';

export type { RenderSummary } from './render-format.ts';

/**
 * The CLI flag a loader or sequence option corresponds to, for errors. (`camera` and `variant`
 * keep the loader's option names, as the CLI has always reported them.)
 */
const cliFlags: Readonly<Record<string, string>> = {
  animation: '--animation',
  time: '--at',
  variants: '--variants',
  cameras: '--cameras',
  frames: '--frames',
  fps: '--fps',
  turntable: '--turntable',
  'turntable.frames': '--turntable',
};

/** Re-labels an INVALID_OPTION error of an API option with the CLI flag that set it. */
export function withCliFlag(error: unknown): unknown {
  if (!isGpuRendererError(error) || error.code !== 'INVALID_OPTION' || error.field === undefined) return error;
  const key = error.field.replace(/\[\d+\]$/, '');
  const flag = cliFlags[key];
  if (flag === undefined) return error;
  return new GpuRendererError('INVALID_OPTION', error.message.slice(error.field.length + 2), { field: flag, cause: error });
}

/** `--animation`: a name the asset has, else a decimal index. */
function animationChoice(animations: readonly GltfAnimationInfo[], text: string | undefined): number | string | undefined {
  if (text === undefined || animations.some((a) => a.name === text)) return text;
  return /^\d+$/.test(text) ? Number(text) : text;
}

/** Loads a glTF asset posed as the command asks (`--animation`, `--at`, `--camera`, `--variant`). */
export async function loadGltfForCommand(
  scenePath: string,
  options: { camera?: string; variant?: string; animation?: string; at?: number; aspectRatio?: number; stderr?: ProgressStream; resourcePolicy?: ResourcePolicy },
): Promise<GltfScene> {
  // Loaded on demand so JSON scenes never pull in the glTF reader and its decoders.
  const { loadGltfScene } = await import('../io/gltf/load-gltf-scene.ts');
  try {
    let gltf = await loadGltfScene(scenePath, { camera: options.camera, variant: options.variant, ...(options.resourcePolicy ? { resourcePolicy: options.resourcePolicy } : {}), ...(options.aspectRatio !== undefined ? { aspectRatio: options.aspectRatio } : {}) });
    if (options.animation !== undefined || options.at !== undefined) {
      gltf = await gltf.pose({ ...(options.animation !== undefined ? { animation: animationChoice(gltf.animations, options.animation) } : {}), ...(options.at !== undefined ? { time: options.at } : {}) });
    }
    for (const warning of gltf.warnings) options.stderr?.write(`warning: ${warning}\n`);
    return gltf;
  } catch (error) {
    throw withCliFlag(error);
  }
}

/**
 * The scene to render: the Cornell box, a glTF 2.0 asset (.glb / .gltf, by extension; its loader
 * warnings go to `stderr`) or a scene JSON file.
 */
export async function loadScene(
  scenePath: string | undefined,
  options: { camera?: string; variant?: string; animation?: string; at?: number; stderr?: ProgressStream; aspectRatio?: number; negativeTexels?: 'zero' | 'error'; resourcePolicy?: ResourcePolicy } = {},
): Promise<WavefrontSceneDescription & { environmentMap?: EnvironmentMapInput }> {
  if (scenePath === undefined) return createCornellBoxScene();
  if (isGltfPath(scenePath)) {
    // Spreading keeps the renderer's scene keys only; the loader's metadata is non-enumerable.
    return { ...(await loadGltfForCommand(scenePath, options)) };
  }
  // Scene JSON: its `uri` images are decoded and its `gltf` references loaded and merged.
  const { loadSceneFile } = await import('../io/scene-file-loader.ts');
  const file = await loadSceneFile(scenePath, {
    negativeTexels: options.negativeTexels ?? 'error',
    resourcePolicy: options.resourcePolicy,
    onNegativeTexels: (report, field) => {
      const text = negativeTexelNote(field, report);
      if (text !== undefined) options.stderr?.write(`note: ${text}\n`);
    },
  });
  for (const warning of file.warnings) options.stderr?.write(`warning: ${warning}\n`);
  return file.scene;
}

/** Adaptive sampling's minimum for the CLI: Cycles' rule for the threshold, at most spp / 4 (and 2 at least). */
export function cliMinimumSamples(command: RenderCommand): number | undefined {
  if (command.noiseThreshold === undefined) return undefined;
  if (command.minSpp !== undefined) return command.minSpp;
  const cycles = defaultAdaptiveSamplingParameters(1, command.noiseThreshold).minimumSamplesPerPixel;
  return Math.max(2, Math.min(cycles, Math.floor(command.spp / 4)));
}

/** The renderer settings of a command (everything but the scene). */
export function rendererSettings(command: RenderCommand): SequenceRendererOptions {
  const minimumSamplesPerPixel = cliMinimumSamples(command);
  return {
    width: command.width,
    height: command.height,
    maxDepth: command.maxDepth,
    samplesPerPixel: command.sppPerFrame,
    seed: command.seed,
    toneMapping: command.toneMapping,
    exposure: command.exposure,
    exposureEv: command.exposureEv,
    aovs: command.aovs.some((a) => a !== 'sampleCount'),
    denoise: command.denoise,
    energyCompensation: command.energyCompensation,
    ...(command.accelerationBuildMode ? { accelerationBuildMode: command.accelerationBuildMode } : {}),
    ...(command.integrator ? { integrator: command.integrator } : {}),
    ...(command.instancing ? { instancing: command.instancing } : {}),
    ...(command.noiseThreshold !== undefined ? { adaptiveThreshold: command.noiseThreshold, minimumSamplesPerPixel } : {}),
  };
}

/** What accumulating one image took; the first frame is counted apart (it runs outside the clock). */
export interface AccumulationStats {
  samplesPerPixel: number;
  stoppedBy: NonNullable<RenderSummary['stoppedBy']>;
  firstFrameMs: number;
  firstSamples: number;
  firstPixelSamples: number;
  firstRays: number;
  /** Pixel samples, rays and time of the frames after the first. */
  pixelSamples: number;
  rays: number;
  renderMs: number;
  invalidSamples: number;
}

/** Progress of one image: the estimate's `remainingSeconds` is always set; `extrapolated` says it is the plain sample-rate extrapolation. */
export type AccumulationProgress = (samples: number, total: number, estimate: ProgressEstimate & { remainingSeconds: number; extrapolated: boolean }) => void;

/**
 * Accumulates the command's samples into `renderer` in increments of --spp-per-frame, until the
 * ceiling, the time limit or (adaptive sampling) convergence, reporting progress after each frame.
 * The first frame runs outside the clock: drivers that compile pipelines on their first dispatch
 * (llvmpipe, some mobile drivers) do so there, so --time and the sample rate measure sampling
 * only. It is an ordinary frame (its samples count), so the cadence is unchanged.
 */
export async function accumulateImage(renderer: WavefrontPathTracingRenderer, command: RenderCommand, report: AccumulationProgress): Promise<AccumulationStats> {
  const pixels = command.width * command.height;
  let pixelSamples = 0;
  let rays = 0;
  let invalidSamples = 0;
  let renderMs = 0;
  let lastFrameMs: number | null = null;
  let stoppedBy: AccumulationStats['stoppedBy'] = 'spp';
  const firstSamples = Math.min(command.sppPerFrame, command.spp);
  const firstStart = performance.now();
  const first = await renderer.renderFrame({ samplesPerPixel: firstSamples });
  const firstFrameMs = performance.now() - firstStart;
  if (first.samplesAdded <= 0 && !first.adaptive) throw new GpuRendererError('INVALID_STATE', 'renderFrame added no samples');
  let accumulated = first.samplesAccumulated;
  invalidSamples += first.radianceDiagnostics.invalidSamples;
  const started = performance.now();
  const deadline = command.timeLimitMs === undefined ? Infinity : started + command.timeLimitMs;
  let converged = first.adaptive !== null && first.adaptive.activePixels === 0;
  if (converged) stoppedBy = 'noise';
  report(accumulated, command.spp, { fraction: converged ? 1 : accumulated / command.spp, remainingSeconds: converged ? 0 : ((command.spp - accumulated) * firstFrameMs) / Math.max(1, accumulated) / 1000, extrapolated: true });
  while (accumulated < command.spp && !converged) {
    const left = deadline - performance.now();
    if (left <= 0) {
      stoppedBy = 'time';
      break;
    }
    const spp = Math.min(command.sppPerFrame, command.spp - accumulated);
    // Close to the time limit a frame gets the time left as its budget (at least one pass).
    const budgeted = Number.isFinite(left) && (lastFrameMs === null || 1.5 * lastFrameMs > left);
    const start = performance.now();
    const stats = await renderer.renderFrame({ samplesPerPixel: spp, ...(budgeted ? { frameTimeBudgetMs: left, minimumSamplesPerPixel: 1 } : {}) });
    lastFrameMs = performance.now() - start;
    renderMs += lastFrameMs;
    if (stats.samplesAdded <= 0 && !stats.adaptive) throw new GpuRendererError('INVALID_STATE', 'renderFrame added no samples');
    accumulated = stats.samplesAccumulated;
    pixelSamples += stats.rays.camera;
    rays += stats.rays.total;
    invalidSamples += stats.radianceDiagnostics.invalidSamples;
    const elapsed = performance.now() - started;
    const sampled = pixelSamples / pixels;
    const estimates = [(command.spp - accumulated) * (elapsed / Math.max(1e-9, sampled))];
    if (Number.isFinite(deadline)) estimates.push(Math.max(0, deadline - performance.now()));
    if (stats.adaptive) estimates.push((stats.adaptive.estimatedRemainingPixelSamples * elapsed) / Math.max(1, pixelSamples));
    const remaining = Math.min(...estimates);
    converged = stats.adaptive !== null && stats.adaptive.activePixels === 0;
    report(accumulated, command.spp, {
      fraction: converged ? 1 : elapsed / (elapsed + remaining),
      remainingSeconds: converged ? 0 : remaining / 1000,
      extrapolated: estimates.length === 1,
      ...(stats.adaptive ? { note: `${((100 * stats.adaptive.activePixels) / pixels).toFixed(0)}% px sampling` } : {}),
    });
    if (converged) {
      stoppedBy = 'noise';
      break;
    }
    if (budgeted && accumulated < command.spp && performance.now() >= deadline) {
      stoppedBy = 'time';
      break;
    }
  }
  return { samplesPerPixel: accumulated, stoppedBy, firstFrameMs, firstSamples, firstPixelSamples: first.rays.camera, firstRays: first.rays.total, pixelSamples, rays, renderMs, invalidSamples };
}

/** What the scene's references may touch: their own folder, and the origins --allow-origin names. */
export function commandResourcePolicy(command: Pick<RenderCommand, 'allowedOrigins'>): ResourcePolicy {
  return { allowedOrigins: command.allowedOrigins ?? [] };
}

export async function runRenderCommand(command: RenderCommand, io: { stderr: ProgressStream } = { stderr: process.stderr }): Promise<RenderSummary> {
  const t0 = performance.now();
  const resourcePolicy = commandResourcePolicy(command);
  const loaded = await loadScene(command.scenePath, {
    camera: command.camera,
    variant: command.variant,
    animation: command.animation,
    at: command.at,
    stderr: io.stderr,
    aspectRatio: command.width / command.height,
    negativeTexels: command.negativeTexels,
    resourcePolicy,
  });
  const { scene: lit, lighting } = await applyCliLighting(loaded, command, (text) => io.stderr.write(`note: ${text}\n`), resourcePolicy);
  const scene = applyCameraFlags(lit, command);
  const renderer: WavefrontPathTracingRenderer = await createWavefrontPathTracingComputeRenderer({ ...rendererSettings(command), ...scene });
  try {
    const pixels = command.width * command.height;
    const progress = createProgressBar(io.stderr);
    progress.update(0, command.spp);
    const stats = await accumulateImage(renderer, command, (done, total, estimate) =>
      // Without a time limit or a noise target done / total is the fraction and the bar extrapolates.
      progress.update(done, total, estimate.extrapolated ? (estimate.note === undefined ? {} : { note: estimate.note }) : estimate),
    );
    progress.finish();
    await writeFrameFile(command.out, await encodeOutput(renderer, command));
    // Rates over the frames after the first; a one-frame render has only the first to go by.
    const steady = stats.renderMs > 0;
    const rateSeconds = (steady ? stats.renderMs : stats.firstFrameMs) / 1000;
    return {
      width: command.width,
      height: command.height,
      samplesPerPixel: stats.samplesPerPixel,
      meanSamplesPerPixel: (stats.firstPixelSamples + stats.pixelSamples) / pixels,
      stoppedBy: stats.stoppedBy,
      ...(command.denoise ? { denoised: renderer.getSnapshot().denoise!.denoiser } : {}),
      aovs: command.aovs,
      firstFrameSeconds: stats.firstFrameMs / 1000,
      firstFrameSamplesPerPixel: stats.firstSamples,
      renderSeconds: stats.renderMs / 1000,
      totalSeconds: (performance.now() - t0) / 1000,
      samplesPerSecond: (steady ? stats.pixelSamples : stats.firstPixelSamples) / rateSeconds,
      rays: stats.firstRays + stats.rays,
      raysPerSecond: (steady ? stats.rays : stats.firstRays) / rateSeconds,
      invalidSamples: stats.invalidSamples,
      adapter: renderer.getSnapshot().adapter,
      lighting,
      geometry: describeGeometry(renderer.getSnapshot()),
      out: command.out,
    };
  } finally {
    renderer.destroy();
  }
}

/**
 * The image file's bytes: a PNG is what the display shows (tone mapped, exposed, denoised if asked);
 * an .exr or .hdr holds linear radiance (the denoised beauty with --denoise, the raw one kept as
 * layer raw.R/G/B in an .exr), with the AOV layers --aov names in an .exr.
 */
export async function encodeOutput(renderer: WavefrontPathTracingRenderer, command: RenderCommand): Promise<Uint8Array> {
  if (command.format === 'png') return encodePng(await renderer.readPixels());
  const raw = await renderer.readRadiance();
  const beauty = command.denoise ? await renderer.readDenoised() : raw;
  const aovs: Partial<Record<WavefrontAovName, Float32Array>> = {};
  for (const name of command.aovs) aovs[name] = (await renderer.readAov(name)).data;
  const layers = command.denoise && command.format === 'exr' ? [{ name: 'raw', channels: ['R', 'G', 'B'], data: raw.data }] : [];
  return encodeImageFile(beauty, command.format, { pixelType: command.half ? 'half' : 'float', aovs, layers });
}
