/**
 * createWavefrontAdaptiveSamplingLevels: a bounded low-to-high ladder of per-frame sampling configs
 * for frame-time governors such as @plasius/gpu-performance. Each level is shaped like the worker
 * manifests' budget levels ({ id, estimatedCostMs, config }) and its config carries exactly the
 * renderFrame options of the adaptive-sampling surface: samplesPerPixel (a ceiling once a frame
 * budget is set), frameTimeBudgetMs, and minimumSamplesPerPixel (the guaranteed floor).
 */
import { GpuRendererError } from '../../errors/gpu-renderer-error.ts';

export interface WavefrontAdaptiveSamplingLevelOptions {
  /** Samples per pixel of the top level; integer 1..65536. */
  maxSamplesPerPixel: number;
  /** Samples every level guarantees (and the bottom level's ceiling); integer 1..max; default 1. */
  minimumSamplesPerPixel?: number;
  /** Number of levels wanted, 1..32; default 4. Fewer are returned when there are not enough distinct sample counts. */
  levels?: number;
  /** Frame time budget of the top level in ms, (0, 10000]; default 1000 / 60. */
  targetFrameTimeMs?: number;
}

export interface WavefrontAdaptiveSamplingLevelConfig {
  readonly samplesPerPixel: number;
  readonly frameTimeBudgetMs: number;
  readonly minimumSamplesPerPixel: number;
}

export interface WavefrontAdaptiveSamplingLevel {
  /** `spp-<samplesPerPixel>`. */
  readonly id: string;
  /** Equal to config.frameTimeBudgetMs: the level never plans to spend more. */
  readonly estimatedCostMs: number;
  readonly config: WavefrontAdaptiveSamplingLevelConfig;
}

function requireIntegerIn(value: unknown, field: string, min: number, max: number): number {
  if (typeof value !== 'number' || !Number.isInteger(value) || value < min || value > max) {
    throw new GpuRendererError('INVALID_OPTION', `expected an integer in [${min}, ${max}], got ${String(value)}`, { field });
  }
  return value;
}

/**
 * Sample counts spaced geometrically from minimumSamplesPerPixel to maxSamplesPerPixel (so each step
 * changes noise by a similar factor: Monte Carlo error falls as 1/sqrt(spp)), rounded to integers
 * and de-duplicated, lowest first. Frame budgets scale with the sample count (path tracing cost is
 * linear in spp), the top level getting targetFrameTimeMs.
 */
export function createWavefrontAdaptiveSamplingLevels(options: WavefrontAdaptiveSamplingLevelOptions): readonly WavefrontAdaptiveSamplingLevel[] {
  if (options === null || typeof options !== 'object') throw new GpuRendererError('INVALID_OPTION', 'expected an options object', { field: 'options' });
  const max = requireIntegerIn(options.maxSamplesPerPixel, 'maxSamplesPerPixel', 1, 65536);
  const min = requireIntegerIn(options.minimumSamplesPerPixel ?? 1, 'minimumSamplesPerPixel', 1, max);
  const count = requireIntegerIn(options.levels ?? 4, 'levels', 1, 32);
  const target = options.targetFrameTimeMs ?? 1000 / 60;
  if (typeof target !== 'number' || !Number.isFinite(target) || target <= 0 || target > 10000) {
    throw new GpuRendererError('INVALID_OPTION', `expected a number in (0, 10000], got ${String(target)}`, { field: 'targetFrameTimeMs' });
  }
  const counts: number[] = [];
  for (let i = 0; i < count; i++) {
    const spp = count === 1 ? max : Math.round(min * Math.pow(max / min, i / (count - 1)));
    if (counts.length === 0 || spp > counts[counts.length - 1]) counts.push(spp);
  }
  return Object.freeze(
    counts.map((samplesPerPixel) => {
      const frameTimeBudgetMs = (target * samplesPerPixel) / max;
      return Object.freeze({
        id: `spp-${samplesPerPixel}`,
        estimatedCostMs: frameTimeBudgetMs,
        config: Object.freeze({ samplesPerPixel, frameTimeBudgetMs, minimumSamplesPerPixel: Math.min(min, samplesPerPixel) }),
      });
    }),
  );
}
