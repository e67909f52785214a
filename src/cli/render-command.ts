/**
 * The `render` command: load a scene, path trace it in small increments with progress until the
 * sample ceiling, the time limit or the noise target, write a PNG, OpenEXR (with AOV layers) or
 * Radiance HDR image.
 */
import { createWavefrontPathTracingComputeRenderer } from '../pathtracer/index.ts';
import type { WavefrontPathTracingRenderer } from '../pathtracer/types.ts';
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { createCornellBoxScene } from '../scene/cornell-box.ts';
import type { WavefrontSceneDescription } from '../scene/types.ts';
import type { EnvironmentMapInput } from '../lighting/environment-map.ts';
import { applyCameraFlags } from './camera-flags.ts';
import { applyEnvironmentFlags, negativeTexelNote } from './environment-flags.ts';
import { writePng } from '../post/png-node.ts';
import { writeImageFile } from '../post/files/image-file.ts';
import type { WavefrontAovName } from '../post/aovs.ts';
import { defaultAdaptiveSamplingParameters } from '../post/adaptive-sampling/converged-mask.ts';
import { createProgressBar, type ProgressStream } from './progress.ts';
import type { RenderSummary } from './render-format.ts';
import { isGltfPath, type RenderCommand } from './args.ts';
import type { ResourcePolicy } from '../io/resource-policy.ts';

export type { RenderSummary } from './render-format.ts';

/**
 * The scene to render: the Cornell box, a glTF 2.0 asset (.glb / .gltf, by extension; its loader
 * warnings go to `stderr`) or a scene JSON file.
 */
export async function loadScene(
  scenePath: string | undefined,
  options: { camera?: string; variant?: string; stderr?: ProgressStream; aspectRatio?: number; negativeTexels?: 'zero' | 'error'; resourcePolicy?: ResourcePolicy } = {},
): Promise<WavefrontSceneDescription & { environmentMap?: EnvironmentMapInput }> {
  if (scenePath === undefined) return createCornellBoxScene();
  const resourcePolicy = options.resourcePolicy;
  if (isGltfPath(scenePath)) {
    // Loaded on demand so JSON scenes never pull in the glTF reader and its decoders.
    const { loadGltfScene } = await import('../io/gltf/load-gltf-scene.ts');
    const gltf = await loadGltfScene(scenePath, { camera: options.camera, variant: options.variant, resourcePolicy, ...(options.aspectRatio !== undefined ? { aspectRatio: options.aspectRatio } : {}) });
    for (const warning of gltf.warnings) options.stderr?.write(`warning: ${warning}\n`);
    // Spreading keeps the renderer's scene keys only; the loader's metadata is non-enumerable.
    return { ...gltf };
  }
  // Scene JSON: its `uri` images are decoded and its `gltf` references loaded and merged.
  const { loadSceneFile } = await import('../io/scene-file-loader.ts');
  const file = await loadSceneFile(scenePath, {
    negativeTexels: options.negativeTexels ?? 'error',
    resourcePolicy,
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

export async function runRenderCommand(command: RenderCommand, io: { stderr: ProgressStream } = { stderr: process.stderr }): Promise<RenderSummary> {
  const t0 = performance.now();
  // What the scene's references may touch: their own folder, and the origins --allow-origin names.
  const resourcePolicy: ResourcePolicy = { allowedOrigins: command.allowedOrigins ?? [] };
  const loaded = await loadScene(command.scenePath, {
    camera: command.camera,
    variant: command.variant,
    stderr: io.stderr,
    aspectRatio: command.width / command.height,
    negativeTexels: command.negativeTexels,
    resourcePolicy,
  });
  const lit = await applyEnvironmentFlags(loaded, command, (text) => io.stderr.write(`note: ${text}\n`), resourcePolicy);
  const scene = applyCameraFlags(lit, command);
  const minimumSamplesPerPixel = cliMinimumSamples(command);
  const renderer: WavefrontPathTracingRenderer = await createWavefrontPathTracingComputeRenderer({
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
    ...(command.noiseThreshold !== undefined ? { adaptiveThreshold: command.noiseThreshold, minimumSamplesPerPixel } : {}),
    ...scene,
  });
  try {
    const pixels = command.width * command.height;
    const progress = createProgressBar(io.stderr);
    let accumulated = 0;
    let pixelSamples = 0;
    let rays = 0;
    let invalidSamples = 0;
    let renderMs = 0;
    let lastFrameMs: number | null = null;
    let stoppedBy: RenderSummary['stoppedBy'] = 'spp';
    progress.update(0, command.spp);
    // The first frame runs outside the clock: drivers that compile pipelines on their first
    // dispatch (llvmpipe, some mobile drivers) do so here, so --time and the sample rate measure
    // sampling only. It is an ordinary frame (its samples count), so the cadence is unchanged.
    const firstSamples = Math.min(command.sppPerFrame, command.spp);
    const firstStart = performance.now();
    const first = await renderer.renderFrame({ samplesPerPixel: firstSamples });
    const firstFrameMs = performance.now() - firstStart;
    if (first.samplesAdded <= 0 && !first.adaptive) throw new GpuRendererError('INVALID_STATE', 'renderFrame added no samples');
    accumulated = first.samplesAccumulated;
    const firstPixelSamples = first.rays.camera;
    const firstRays = first.rays.total;
    invalidSamples += first.radianceDiagnostics.invalidSamples;
    const started = performance.now();
    const deadline = command.timeLimitMs === undefined ? Infinity : started + command.timeLimitMs;
    let converged = first.adaptive !== null && first.adaptive.activePixels === 0;
    if (converged) stoppedBy = 'noise';
    progress.update(accumulated, command.spp);
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
      progress.update(accumulated, command.spp, {
        ...(estimates.length > 1 ? { fraction: converged ? 1 : elapsed / (elapsed + remaining), remainingSeconds: remaining / 1000 } : {}),
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
    progress.finish();
    await writeOutput(renderer, command);
    // Rates over the frames after the first; a one-frame render has only the first to go by.
    const steady = renderMs > 0;
    const rateSeconds = (steady ? renderMs : firstFrameMs) / 1000;
    return {
      width: command.width,
      height: command.height,
      samplesPerPixel: accumulated,
      meanSamplesPerPixel: (firstPixelSamples + pixelSamples) / pixels,
      stoppedBy,
      ...(command.denoise ? { denoised: renderer.getSnapshot().denoise!.denoiser } : {}),
      aovs: command.aovs,
      firstFrameSeconds: firstFrameMs / 1000,
      firstFrameSamplesPerPixel: firstSamples,
      renderSeconds: renderMs / 1000,
      totalSeconds: (performance.now() - t0) / 1000,
      samplesPerSecond: (steady ? pixelSamples : firstPixelSamples) / rateSeconds,
      rays: firstRays + rays,
      raysPerSecond: (steady ? rays : firstRays) / rateSeconds,
      invalidSamples,
      adapter: renderer.getSnapshot().adapter,
      out: command.out,
    };
  } finally {
    renderer.destroy();
  }
}

/**
 * Writes the image: a PNG is what the display shows (tone mapped, exposed, denoised if asked); an
 * .exr or .hdr holds linear radiance (the denoised beauty with --denoise, the raw one kept as layer
 * raw.R/G/B in an .exr), with the AOV layers --aov names in an .exr.
 */
async function writeOutput(renderer: WavefrontPathTracingRenderer, command: RenderCommand): Promise<void> {
  if (command.format === 'png') {
    await writePng(command.out, await renderer.readPixels());
    return;
  }
  const raw = await renderer.readRadiance();
  const beauty = command.denoise ? await renderer.readDenoised() : raw;
  const aovs: Partial<Record<WavefrontAovName, Float32Array>> = {};
  for (const name of command.aovs) aovs[name] = (await renderer.readAov(name)).data;
  const layers = command.denoise && command.format === 'exr' ? [{ name: 'raw', channels: ['R', 'G', 'B'], data: raw.data }] : [];
  await writeImageFile(command.out, beauty, { format: command.format, pixelType: command.half ? 'half' : 'float', aovs, layers });
}
