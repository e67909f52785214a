import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { queueCounterSlots, rendererWavefrontComputeWorkgroupSize } from '../gpu-layout/constants.ts';
import { beginFrame, endFrame, finishFrame, renderPasses, submitStep } from './frame-passes.ts';
import { emitProgress, progressOf } from './frame-progress.ts';
import { frameStatsFromCounters, type FrameReadout } from './frame-stats.ts';
import { parseRenderFrameOptions } from './output-options.ts';
import type { WavefrontOutputState } from './output-types.ts';
import { rendererMemory } from './renderer-resources.ts';
import { assertUsable, type FrameOutcome, type RendererState } from './renderer-state.ts';
import type { WavefrontFrameStats, WavefrontMemoryStats, WavefrontRenderFrameOptions } from './types.ts';

/** The output settings a frame's statistics and the snapshot report. */
export function outputState(s: RendererState): WavefrontOutputState {
  const o = s.config.output;
  return {
    maxFramePassesPerSubmission: o.maxFramePassesPerSubmission,
    presentationOutput: o.presentationOutput,
    exposureEv: o.exposureEv,
    adaptiveSampling: o.adaptive,
    denoise: o.denoise,
    featureFlags: o.features.featureFlags,
    transportExperiments: o.features.transportExperiments,
    transportExperimentFlags: o.features.transportExperimentFlags,
    transportExperimentRequestedFlags: o.features.transportExperimentRequestedFlags,
  };
}

/**
 * Submits the frame as soon as fewer than framesInFlight frames await their statistics, and
 * resolves to its statistics once they come back (through the readback ring). A caller that
 * requests the next frame before awaiting this one keeps the GPU fed: nothing between two
 * submissions waits for the GPU.
 */
export async function renderFrame(s: RendererState, options?: WavefrontRenderFrameOptions): Promise<WavefrontFrameStats> {
  assertUsable(s);
  const frame = parseRenderFrameOptions(options, s.config.samplesPerPixel);
  const started = performance.now();
  let submitted: { outcome: FrameOutcome; denoised: boolean; frameNumber: number; samplesAccumulated: number; memory: WavefrontMemoryStats; readout: Promise<FrameReadout> };
  let readout: FrameReadout;
  try {
    submitted = await s.submissions.after(async () => {
      const slot = await s.readbacks.acquire();
      assertUsable(s);
      const outcome = await renderPasses(s, frame, started, slot);
      const denoised = finishFrame(s, outcome.tally, slot);
      outcome.submissions += 1;
      return { outcome, denoised, frameNumber: s.frameCount, samplesAccumulated: s.samplesAccumulated, memory: rendererMemory(s.buffers, s.textureBytes), readout: s.readbacks.read(slot) };
    });
    readout = await submitted.readout;
  } catch (error) {
    assertUsable(s);
    throw error;
  }
  const { outcome } = submitted;
  const wallTimeMs = performance.now() - started;
  const pixels = s.config.width * s.config.height;
  // The camera-ray counter is exact where the CPU's step accounting used a stale list length.
  const cameraRays = readout.counters[queueCounterSlots.cameraRays]!;
  s.pixelSamplesAccumulated += cameraRays - outcome.pixelSamples;
  outcome.pixelSamples = cameraRays;
  const settings = s.config.output.adaptive;
  const counts = s.adaptive?.counts;
  const stats = frameStatsFromCounters(readout.counters, {
    frame: submitted.frameNumber,
    samplesAdded: outcome.samplesAdded,
    samplesAccumulated: submitted.samplesAccumulated,
    samplesPerPixel: frame.ceiling,
    frameTimeBudgetMs: frame.budgetMs,
    gpuTimeMs: readout.gpuTimeMs,
    wallTimeMs,
    memory: submitted.memory,
    tiles: Math.ceil(pixels / outcome.wavePaths),
    waves: outcome.waves,
    wavePaths: outcome.wavePaths,
    submissions: outcome.submissions,
    deviceLost: s.deviceLost,
    gpuParallelism: outcome.tally.report(s.device.limits, rendererWavefrontComputeWorkgroupSize),
    adaptive:
      settings && counts
        ? {
          threshold: settings.threshold,
          minimumSamplesPerPixel: settings.minimumSamplesPerPixel,
          activePixels: counts.activePixels,
          convergedPixels: pixels - counts.activePixels,
          pixelSamples: outcome.pixelSamples,
          meanSamplesPerPixel: s.pixelSamplesAccumulated / pixels,
          estimatedRemainingPixelSamples: counts.estimatedRemainingPixelSamples,
        }
        : null,
    denoised: submitted.denoised,
    output: outputState(s),
  });
  emitProgress(s, progressOf(s, frame, outcome, wallTimeMs, true, submitted.frameNumber, submitted.samplesAccumulated), frame.onProgress);
  return stats;
}

/** Submits one frame's work without waiting for it (no frameTimeBudgetMs). */
export function renderOnce(s: RendererState, options?: WavefrontRenderFrameOptions): void {
  assertUsable(s);
  const frame = parseRenderFrameOptions(options, s.config.samplesPerPixel);
  if (frame.budgetMs !== null) throw new GpuRendererError('INVALID_OPTION', 'a frame time budget needs renderFrame, which waits for the GPU', { field: 'frameTimeBudgetMs' });
  void s.submissions.after(() => {
    if (s.destroyed || s.deviceLost) return;
    const outcome = beginFrame(s);
    // One step of all the passes; adaptive sampling's count lands when the GPU gets there and sizes
    // a later frame (nothing here waits for it).
    if (!(s.adaptive && s.adaptive.counts.activePixels === 0)) void submitStep(s, outcome, frame.ceiling, null)?.catch(() => undefined);
    endFrame(s, outcome);
    finishFrame(s, outcome.tally, null);
  }).catch(() => undefined);
}
