/**
 * Reading the path tracer harness output of either version, and the per-scene summary of the
 * alternated runs: median throughput per version, the ratio of medians (current / baseline) and
 * the per-round paired ratios, whose spread shows the measurement noise. Throughput is given per
 * wall-clock second and, where known, per CPU second of the driver's threads (cpu-clock.ts).
 */

/** One scene measured by one child process, in units of 1/s. */
export interface SceneMeasurement {
  scene: string;
  triangles: number | null;
  resolution: string | null;
  spp: number | null;
  seconds: number | null;
  samplesPerSecond: number;
  raysPerSecond: number | null;
  /** Samples per CPU second off the main thread (cpu-clock.ts); null when not measured. */
  samplesPerWorkerCpuSecond: number | null;
  /** Cores' worth of CPU other processes used during the timed frame; null when not measured. */
  otherLoadCores: number | null;
  adapter: string | null;
}

export type VersionLabel = 'baseline' | 'current';

export interface PathTracerRun {
  version: VersionLabel;
  /** 1-based; baseline round r runs just before current round r. */
  round: number;
  /** Wall clock of the whole child process (setup, BVH builds, warm-up and timed frames). */
  childSeconds: number;
  scenes: SceneMeasurement[];
  error?: string;
}

export interface Spread {
  median: number;
  min: number;
  max: number;
  values: number[];
}

export interface VersionSceneSummary {
  runs: number;
  samplesPerSecond: Spread;
  raysPerSecond: Spread | null;
  samplesPerWorkerCpuSecond: Spread | null;
  otherLoadCores: Spread | null;
  adapter: string | null;
  triangles: number | null;
  resolution: string | null;
  spp: number | null;
}

export interface SceneComparison {
  scene: string;
  baseline: VersionSceneSummary | null;
  current: VersionSceneSummary | null;
  /** current / baseline of the medians; null without both versions. */
  samplesPerSecondRatio: number | null;
  raysPerSecondRatio: number | null;
  samplesPerWorkerCpuSecondRatio: number | null;
  /** current / baseline of samples/s within each round (the two adjacent child processes). */
  pairedSamplesPerSecondRatios: number[];
  pairedSamplesPerWorkerCpuSecondRatios: number[];
  /** Set when the two versions did not measure the same workload (scene size, resolution, spp). */
  mismatch: string | null;
}

export function median(values: readonly number[]): number {
  if (values.length === 0) throw new Error('median of no values');
  const s = [...values].sort((a, b) => a - b);
  const m = s.length >> 1;
  return s.length % 2 ? s[m]! : (s[m - 1]! + s[m]!) / 2;
}

function spread(values: number[]): Spread {
  return { median: median(values), min: Math.min(...values), max: Math.max(...values), values };
}

const finite = (v: unknown): v is number => typeof v === 'number' && Number.isFinite(v);
const positive = (v: unknown): v is number => finite(v) && v > 0;

function pixels(resolution: string | null): number | null {
  const m = resolution ? /^(\d+)x(\d+)$/.exec(resolution) : null;
  return m ? Number(m[1]) * Number(m[2]) : null;
}

/**
 * Reads `{ rows: [...] }` from runPathTracerBenchmark(). Two row shapes exist: the current harness
 * (samplesPerSecond, raysPerSecond in 1/s) and the one before it (display columns 'samples/s (M)'
 * and 'rays/s (M)' rounded to 3 decimals; samples/s is recomputed from resolution, spp and seconds
 * there, which keeps more digits).
 */
export function readPathTracerResult(value: unknown): SceneMeasurement[] {
  const rows = (value as { rows?: unknown } | null)?.rows;
  if (!Array.isArray(rows) || rows.length === 0) throw new Error('the harness result has no rows');
  return rows.map((raw: unknown, i) => {
    const row = (raw ?? {}) as Record<string, unknown>;
    if (typeof row.scene !== 'string') throw new Error(`rows[${i}] has no scene name`);
    const resolution = typeof row.resolution === 'string' ? row.resolution : null;
    const spp = finite(row.spp) ? row.spp : null;
    const seconds = positive(row.seconds) ? row.seconds : null;
    const px = pixels(resolution);
    let samplesPerSecond: number | null = null;
    if (positive(row.samplesPerSecond)) samplesPerSecond = row.samplesPerSecond;
    else {
      if (px !== null && spp !== null && seconds !== null) samplesPerSecond = (px * spp) / seconds;
      else if (positive(row['samples/s (M)'])) samplesPerSecond = row['samples/s (M)'] * 1e6;
    }
    if (samplesPerSecond === null) throw new Error(`rows[${i}] (${row.scene}) has no samples/s`);
    let raysPerSecond: number | null = null;
    if (positive(row.raysPerSecond)) raysPerSecond = row.raysPerSecond;
    else if (positive(row['rays/s (M)'])) raysPerSecond = row['rays/s (M)'] * 1e6;
    let samplesPerWorkerCpuSecond: number | null = null;
    if (positive(row.workerCpuSeconds) && px !== null && spp !== null) samplesPerWorkerCpuSecond = (px * spp) / row.workerCpuSeconds;
    return {
      scene: row.scene,
      triangles: finite(row.triangles) ? row.triangles : null,
      resolution,
      spp,
      seconds,
      samplesPerSecond,
      raysPerSecond,
      samplesPerWorkerCpuSecond,
      otherLoadCores: finite(row.otherLoadCores) ? row.otherLoadCores : null,
      adapter: typeof row.adapter === 'string' ? row.adapter : null,
    };
  });
}

function summarizeVersion(measurements: SceneMeasurement[]): VersionSceneSummary | null {
  if (measurements.length === 0) return null;
  const rays = measurements.map((m) => m.raysPerSecond).filter((r): r is number => r !== null);
  const cpu = measurements.map((m) => m.samplesPerWorkerCpuSecond).filter((r): r is number => r !== null);
  const load = measurements.map((m) => m.otherLoadCores).filter((r): r is number => r !== null);
  const first = measurements[0]!;
  return {
    runs: measurements.length,
    samplesPerSecond: spread(measurements.map((m) => m.samplesPerSecond)),
    raysPerSecond: rays.length === measurements.length ? spread(rays) : null,
    samplesPerWorkerCpuSecond: cpu.length === measurements.length ? spread(cpu) : null,
    otherLoadCores: load.length === measurements.length ? spread(load) : null,
    adapter: first.adapter,
    triangles: first.triangles,
    resolution: first.resolution,
    spp: first.spp,
  };
}

function workloadMismatch(a: VersionSceneSummary, b: VersionSceneSummary): string | null {
  const differences: string[] = [];
  for (const key of ['triangles', 'resolution', 'spp'] as const) {
    if (a[key] !== null && b[key] !== null && a[key] !== b[key]) differences.push(`${key} ${String(a[key])} vs ${String(b[key])}`);
  }
  return differences.length ? `baseline and current measured different workloads: ${differences.join(', ')}` : null;
}

/** Per scene (in the order scenes first appear, current version first), both versions side by side. */
export function summarizeRuns(runs: readonly PathTracerRun[]): SceneComparison[] {
  const ordered = [...runs.filter((r) => r.version === 'current'), ...runs.filter((r) => r.version === 'baseline')];
  const names = [...new Set(ordered.flatMap((r) => r.scenes.map((s) => s.scene)))];
  return names.map((scene) => {
    const of = (version: VersionLabel): Array<{ round: number; m: SceneMeasurement }> =>
      runs.filter((r) => r.version === version).flatMap((r) => r.scenes.filter((s) => s.scene === scene).map((m) => ({ round: r.round, m })));
    const baselineRuns = of('baseline');
    const currentRuns = of('current');
    const baseline = summarizeVersion(baselineRuns.map((x) => x.m));
    const current = summarizeVersion(currentRuns.map((x) => x.m));
    const paired: number[] = [];
    const pairedCpu: number[] = [];
    for (const c of currentRuns) {
      const b = baselineRuns.find((x) => x.round === c.round);
      if (!b) continue;
      paired.push(c.m.samplesPerSecond / b.m.samplesPerSecond);
      if (c.m.samplesPerWorkerCpuSecond !== null && b.m.samplesPerWorkerCpuSecond !== null) pairedCpu.push(c.m.samplesPerWorkerCpuSecond / b.m.samplesPerWorkerCpuSecond);
    }
    const both = baseline !== null && current !== null;
    return {
      scene,
      baseline,
      current,
      samplesPerSecondRatio: both ? current.samplesPerSecond.median / baseline.samplesPerSecond.median : null,
      raysPerSecondRatio: both && current.raysPerSecond && baseline.raysPerSecond ? current.raysPerSecond.median / baseline.raysPerSecond.median : null,
      samplesPerWorkerCpuSecondRatio:
        both && current.samplesPerWorkerCpuSecond && baseline.samplesPerWorkerCpuSecond ? current.samplesPerWorkerCpuSecond.median / baseline.samplesPerWorkerCpuSecond.median : null,
      pairedSamplesPerSecondRatios: paired,
      pairedSamplesPerWorkerCpuSecondRatios: pairedCpu,
      mismatch: both ? workloadMismatch(baseline, current) : null,
    };
  });
}
