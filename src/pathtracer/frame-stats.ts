import { LUMINANCE_FRACTION_BITS, queueCounterCount, queueCounterSlots } from '../gpu-layout/constants.ts';
import { BufferUsage, MapMode } from '../gpu/webgpu-constants.ts';
import type { WavefrontAdaptiveFrameStats, WavefrontGpuParallelism, WavefrontOutputState, WavefrontRadianceDiagnostics, WavefrontTerminalRadiance } from './output-types.ts';
import type { WavefrontFrameStats, WavefrontMemoryStats } from './types.ts';

/** Byte stride of the slots of the timestamp resolve buffer (resolveQuerySet offsets are 256-aligned). */
export const timestampResolveStride = 256;

/** What a frame's readback holds once mapped: its statistics words and its GPU time. */
export interface FrameReadout {
  counters: Uint32Array;
  gpuTimeMs: number | null;
}

interface ReadbackSlot {
  index: number;
  counters: GPUBuffer;
  times: GPUBuffer | null;
  /** Settles once the slot's last readback was mapped and copied out (the slot is free again). */
  busy: Promise<unknown> | null;
}

/**
 * A ring of staging buffers through which frame statistics come back without stalling the next
 * submission: each frame copies the statistics block of the `queues` buffer (and resolves its pair of
 * timestamp queries) into its own slot, and a new frame waits only when every slot still awaits
 * its mapping, so at most `slots` frames are in flight.
 */
export class FrameReadbackRing {
  readonly timing: { querySet: GPUQuerySet; resolve: GPUBuffer } | null;
  private readonly ring: ReadbackSlot[];
  private next = 0;

  constructor(device: GPUDevice, slots: number, timing: { querySet: GPUQuerySet; resolve: GPUBuffer } | null) {
    this.timing = timing;
    this.ring = Array.from({ length: slots }, (_, index) => ({
      index,
      counters: device.createBuffer({ label: `frame statistics ${index}`, size: queueCounterCount * 4, usage: BufferUsage.MAP_READ | BufferUsage.COPY_DST }),
      times: timing ? device.createBuffer({ label: `frame timestamps ${index}`, size: 16, usage: BufferUsage.MAP_READ | BufferUsage.COPY_DST }) : null,
      busy: null,
    }));
  }

  get slots(): number {
    return this.ring.length;
  }

  /** The next slot, once it is free (the frame `slots` frames earlier has been read). */
  async acquire(): Promise<number> {
    const slot = this.ring[this.next]!;
    this.next = (this.next + 1) % this.ring.length;
    if (slot.busy) await slot.busy;
    return slot.index;
  }

  /** Timestamp writes of a compute pass of the frame in `slot`: begin at its first pass, end at every pass (the last wins). */
  timestampWrites(slot: number, first: boolean): GPUComputePassTimestampWrites | undefined {
    if (!this.timing) return undefined;
    return { querySet: this.timing.querySet, ...(first ? { beginningOfPassWriteIndex: 2 * slot } : {}), endOfPassWriteIndex: 2 * slot + 1 };
  }

  /** Encodes the copies of the statistics (and the resolved timestamps) into `slot`. */
  encodeCopy(encoder: GPUCommandEncoder, slot: number, queues: GPUBuffer): void {
    const s = this.ring[slot]!;
    encoder.copyBufferToBuffer(queues, 0, s.counters, 0, queueCounterCount * 4);
    if (this.timing && s.times) {
      encoder.resolveQuerySet(this.timing.querySet, 2 * slot, 2, this.timing.resolve, timestampResolveStride * slot);
      encoder.copyBufferToBuffer(this.timing.resolve, timestampResolveStride * slot, s.times, 0, 16);
    }
  }

  /** Maps `slot` after the submission that copied into it; the slot is free again once this settles. */
  read(slot: number): Promise<FrameReadout> {
    const s = this.ring[slot]!;
    const readout = (async (): Promise<FrameReadout> => {
      await Promise.all([s.counters.mapAsync(MapMode.READ), s.times?.mapAsync(MapMode.READ)]);
      try {
        const counters = new Uint32Array(s.counters.getMappedRange().slice(0));
        let gpuTimeMs: number | null = null;
        if (s.times) {
          const t = new BigUint64Array(s.times.getMappedRange().slice(0));
          gpuTimeMs = t[1]! > t[0]! ? Number(t[1]! - t[0]!) / 1e6 : null;
        }
        return { counters, gpuTimeMs };
      } finally {
        s.counters.unmap();
        s.times?.unmap();
      }
    })();
    s.busy = readout.catch(() => undefined);
    return readout;
  }

  destroy(): void {
    for (const s of this.ring) {
      s.counters.destroy();
      s.times?.destroy();
    }
    this.timing?.querySet.destroy();
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
  wavePaths: number;
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
    wavePaths: frame.wavePaths,
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
