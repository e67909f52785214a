/**
 * Timed frames of several live renderers in turn, `rounds` times (versions alternated, so a change
 * of machine load falls on all of them): per renderer and round, samples/s and rays/s by the wall
 * clock, samples per CPU-second of the process's worker threads (cpu-clock.ts) and other
 * processes' load.
 */
import { cpuMark, otherLoadCores, workerCpuSeconds } from './cpu-clock.ts';

export interface Spread {
  median: number;
  min: number;
  max: number;
  all: number[];
}

export function spread(values: number[]): Spread {
  const s = [...values].sort((a, b) => a - b);
  const m = s.length >> 1;
  return { median: s.length % 2 ? s[m]! : (s[m - 1]! + s[m]!) / 2, min: s[0]!, max: s[s.length - 1]!, all: values };
}

interface TimedRenderer {
  renderFrame(options: { samplesPerPixel: number }): Promise<{ rays: { total: number } }>;
}

/** Per renderer (outer index) and round (inner): the figures of one timed frame. */
export interface RoundFigures {
  samples: number[][];
  rays: number[][];
  samplesPerWorkerCpuSecond: number[][];
  /** Other processes' load in cores, per round where it could be measured. */
  otherLoadCores: number[][];
}

export async function timedRounds(renderers: readonly TimedRenderer[], pixels: number, spp: number, rounds: number, onRound: (round: number, samples: number[][]) => void): Promise<RoundFigures> {
  const figures: RoundFigures = { samples: [], rays: [], samplesPerWorkerCpuSecond: [], otherLoadCores: [] };
  for (const list of Object.values(figures) as number[][][]) renderers.forEach(() => list.push([]));
  for (let r = 0; r < rounds; r++) {
    for (let k = 0; k < renderers.length; k++) {
      const from = cpuMark();
      const stats = await renderers[k]!.renderFrame({ samplesPerPixel: spp });
      const to = cpuMark();
      const seconds = (to.wallMs - from.wallMs) / 1000;
      figures.samples[k]!.push((pixels * spp) / seconds);
      figures.rays[k]!.push(stats.rays.total / seconds);
      figures.samplesPerWorkerCpuSecond[k]!.push((pixels * spp) / workerCpuSeconds(from, to));
      const load = otherLoadCores(from, to);
      if (load !== null) figures.otherLoadCores[k]!.push(load);
    }
    onRound(r, figures.samples);
  }
  return figures;
}

/** The throughput columns of a benchmark row, from the rounds of renderer `k`. */
export interface RoundRow {
  resolution: string;
  spp: number;
  samplesPerSecond: Spread;
  raysPerSecond: Spread;
  /** Samples per CPU-second of the threads other than the main one (CPU adapters), or null. */
  samplesPerWorkerCpuSecond: Spread | null;
  /** Cores' worth of other processes' CPU during the timed frames: median, max. */
  otherLoadCores: { median: number; max: number } | null;
}

export function roundFigures(figures: RoundFigures, k: number, cpuAdapter: boolean, size: number, spp: number): RoundRow {
  const other = figures.otherLoadCores[k]!;
  return {
    resolution: `${size}x${size}`,
    spp,
    samplesPerSecond: spread(figures.samples[k]!),
    raysPerSecond: spread(figures.rays[k]!),
    samplesPerWorkerCpuSecond: cpuAdapter ? spread(figures.samplesPerWorkerCpuSecond[k]!) : null,
    otherLoadCores: other.length ? { median: spread(other).median, max: Math.max(...other) } : null,
  };
}
