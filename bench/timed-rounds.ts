/**
 * Timed frames of several live renderers in turn, `rounds` times (versions alternated, so a change
 * of machine load falls on all of them): per renderer and round, samples/s and rays/s by the wall
 * clock, samples per CPU-second of the process's worker threads (cpu-clock.ts) and other
 * processes' load.
 */
import { cpuMark, otherLoadCores, workerCpuSeconds } from './cpu-clock.ts';

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
