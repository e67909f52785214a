import { LUMINANCE_FRACTION_BITS, queueCounterCount, queueCounterSlots } from '../gpu-layout/constants.ts';
import { BufferUsage, MapMode } from '../gpu/webgpu-constants.ts';
import type { WavefrontAdaptiveFrameStats, WavefrontGpuParallelism, WavefrontOutputState, WavefrontRadianceDiagnostics, WavefrontTerminalRadiance } from './output-types.ts';
import type { WavefrontFrameStats, WavefrontMemoryStats } from './types.ts';

/** Staging copies of the counters (and GPU timestamps) a frame reads back. */
export interface FrameReadback {
  counters: GPUBuffer;
  times: GPUBuffer | null;
}

/** Encodes the copies of the counter buffer and resolved timestamps into mappable buffers. */
export function encodeFrameReadback(device: GPUDevice, encoder: GPUCommandEncoder, counters: GPUBuffer, timing: { querySet: GPUQuerySet; resolve: GPUBuffer } | null): FrameReadback {
  const bytes = queueCounterCount * 4;
  const staging = device.createBuffer({ size: bytes, usage: BufferUsage.MAP_READ | BufferUsage.COPY_DST });
  encoder.copyBufferToBuffer(counters, 0, staging, 0, bytes);
  let times: GPUBuffer | null = null;
  if (timing) {
    times = device.createBuffer({ size: 16, usage: BufferUsage.MAP_READ | BufferUsage.COPY_DST });
    encoder.resolveQuerySet(timing.querySet, 0, 2, timing.resolve, 0);
    encoder.copyBufferToBuffer(timing.resolve, 0, times, 0, 16);
  }
  return { counters: staging, times };
}

/** Maps the readback; returns the counters and the GPU time (ms) where timestamps exist. */
export async function readFrameReadback(r: FrameReadback): Promise<{ counters: Uint32Array; gpuTimeMs: number | null }> {
  try {
    await r.counters.mapAsync(MapMode.READ);
    const counters = new Uint32Array(r.counters.getMappedRange().slice(0));
    let gpuTimeMs: number | null = null;
    if (r.times) {
      await r.times.mapAsync(MapMode.READ);
      const t = new BigUint64Array(r.times.getMappedRange().slice(0));
      gpuTimeMs = t[1]! > t[0]! ? Number(t[1]! - t[0]!) / 1e6 : null;
    }
    return { counters, gpuTimeMs };
  } finally {
    r.counters.destroy();
    r.times?.destroy();
  }
}

/** A 64-bit fixed-point luminance tally (lo, hi words; LUMINANCE_FRACTION_BITS fraction bits). */
function fixedPoint(counters: Uint32Array, lo: number): number {
  return (counters[lo]! + counters[lo + 1]! * 2 ** 32) / 2 ** LUMINANCE_FRACTION_BITS;
}

/** The terminal-radiance diagnostics from the counters: mean luminance per pixel sample by source. */
export function terminalRadianceFromCounters(counters: Uint32Array): WavefrontTerminalRadiance {
  const samples = counters[queueCounterSlots.cameraRays]!;
  const per = (v: number): number => (samples > 0 ? v / samples : 0);
  const total = fixedPoint(counters, queueCounterSlots.totalLuminanceLo);
  const emitter = fixedPoint(counters, queueCounterSlots.emitterLuminanceLo);
  const environment = fixedPoint(counters, queueCounterSlots.environmentLuminanceLo);
  return {
    totalLuminance: per(total),
    emitterLuminance: per(emitter),
    environmentLuminance: per(environment),
    // The per-workgroup fixed-point rounding can leave a few ULPs of difference; never negative.
    directLightLuminance: per(Math.max(0, total - emitter - environment)),
    ambientResidualLuminance: 0,
    ambientResidualShare: 0,
    samples,
  };
}

/** What the renderer knows about the frame besides its counters. */
export interface FrameFacts {
  frame: number;
  samplesAdded: number;
  samplesAccumulated: number;
  /** The call's samplesPerPixel: a ceiling when a budget or adaptive sampling cut the frame short. */
  samplesPerPixel: number;
  frameTimeBudgetMs: number | null;
  gpuTimeMs: number | null;
  wallTimeMs: number;
  memory: WavefrontMemoryStats;
  tiles: number;
  waves: number;
  submissions: number;
  deviceLost: boolean;
  gpuParallelism: WavefrontGpuParallelism;
  adaptive: WavefrontAdaptiveFrameStats | null;
  denoised: boolean;
  output: WavefrontOutputState;
}

export function frameStatsFromCounters(counters: Uint32Array, frame: FrameFacts): WavefrontFrameStats {
  const c = (name: keyof typeof queueCounterSlots): number => counters[queueCounterSlots[name]]!;
  const camera = c('cameraRays');
  const extension = c('extensionRays');
  const shadow = c('shadowRays');
  const radianceDiagnostics: WavefrontRadianceDiagnostics = {
    invalidSamples: c('invalidPathSamples'),
    invalidContributions: c('invalidSamples'),
    legacyClampEquivalentSamples: c('clampEquivalentSamples'),
  };
  const seconds = frame.wallTimeMs / 1000;
  return {
    frame: frame.frame,
    samplesAdded: frame.samplesAdded,
    samplesAccumulated: frame.samplesAccumulated,
    samplesPerPixel: frame.samplesPerPixel,
    renderedSamplesPerPixel: frame.samplesAdded,
    frameTimeBudgetMs: frame.frameTimeBudgetMs,
    rays: { camera, extension, shadow, total: camera + extension + shadow },
    terminations: {
      russianRoulette: c('russianRouletteTerminations'),
      maxDepth: c('maxDepthTerminations'),
      escaped: c('escapedPaths'),
      absorbed: c('absorbedPaths'),
      invalidBsdfSample: c('invalidBsdfSamples'),
      invalidThroughput: c('invalidThroughputTerminations'),
    },
    invalidSamples: radianceDiagnostics.invalidSamples,
    radianceDiagnostics,
    terminalRadiance: terminalRadianceFromCounters(counters),
    traversalFallbacks: c('traversalFallbacks'),
    gpuTimeMs: frame.gpuTimeMs,
    wallTimeMs: frame.wallTimeMs,
    memory: frame.memory,
    tiles: frame.tiles,
    waves: frame.waves,
    adaptive: frame.adaptive,
    denoised: frame.denoised,
    gpuParallelism: frame.gpuParallelism,
    transportGuardrails: {
      jobsPerFrame: frame.waves,
      jobsPerSecond: seconds > 0 ? frame.waves / seconds : 0,
      jobsPerSubmission: frame.submissions > 0 ? frame.waves / frame.submissions : 0,
      submissions: frame.submissions,
      queueOverflow: 0,
      radianceDiagnostics,
      trackedMemoryBytes: frame.memory.totalBytes,
      deviceLost: frame.deviceLost,
    },
    ...frame.output,
  };
}
