import { queueCounterCount, queueCounterSlots } from '../gpu-layout/constants.ts';
import { BufferUsage, MapMode } from '../gpu/webgpu-constants.ts';
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

export function frameStatsFromCounters(
  counters: Uint32Array,
  frame: { frame: number; samplesAdded: number; samplesAccumulated: number; gpuTimeMs: number | null; wallTimeMs: number; memory: WavefrontMemoryStats; tiles: number; waves: number },
): WavefrontFrameStats {
  const c = (name: keyof typeof queueCounterSlots): number => counters[queueCounterSlots[name]]!;
  const camera = c('cameraRays');
  const extension = c('extensionRays');
  const shadow = c('shadowRays');
  return {
    frame: frame.frame,
    samplesAdded: frame.samplesAdded,
    samplesAccumulated: frame.samplesAccumulated,
    rays: { camera, extension, shadow, total: camera + extension + shadow },
    terminations: {
      russianRoulette: c('russianRouletteTerminations'),
      maxDepth: c('maxDepthTerminations'),
      escaped: c('escapedPaths'),
      absorbed: c('absorbedPaths'),
      invalidBsdfSample: c('invalidBsdfSamples'),
    },
    invalidSamples: c('invalidSamples'),
    traversalFallbacks: c('traversalFallbacks'),
    gpuTimeMs: frame.gpuTimeMs,
    wallTimeMs: frame.wallTimeMs,
    memory: frame.memory,
    tiles: frame.tiles,
    waves: frame.waves,
  };
}
