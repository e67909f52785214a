/**
 * Child process of the path tracer comparison: `node bench/pathtracer-child.ts <module URL> [--probe]`.
 * Imports one version's bench/pathtracer.ts (this checkout's or the baseline worktree's), runs its
 * runPathTracerBenchmark() on a WebGPU device of its own, and prints the result as one JSON line
 * after RESULT_PREFIX (anything else the harness prints is ignored by the parent). `--probe` only
 * checks that the module and its imports load.
 *
 * Rows without `workerCpuSeconds` (harnesses older than that field) get it, and `otherLoadCores`,
 * here: performance.now() is wrapped, for every version alike, to also note CPU times (two getrusage
 * calls and a read of /proc/stat, some µs), and the timed frame is found among those notes by its
 * reported duration (cpu-clock.ts).
 */
import { RESULT_PREFIX } from './child-protocol.ts';
import { cpuMark, findTimedInterval, otherLoadCores, workerCpuSeconds } from './cpu-clock.ts';
import type { CpuMark } from './cpu-clock.ts';

const [moduleUrl, mode] = process.argv.slice(2);
if (!moduleUrl) {
  console.error('usage: node bench/pathtracer-child.ts <module URL> [--probe]');
  process.exit(2);
}

function emit(value: unknown): Promise<void> {
  return new Promise((resolve) => process.stdout.write(`\n${RESULT_PREFIX}${JSON.stringify(value)}\n`, () => resolve()));
}

const MAX_MARKS = 200_000;
const marks: CpuMark[] = [];
const wallNow = performance.now.bind(performance);
performance.now = (): number => {
  const t = wallNow();
  if (marks.length < MAX_MARKS) marks.push(cpuMark(t));
  return t;
};

/** Adds workerCpuSeconds to rows that lack it; `seconds` of those harnesses is rounded to ms. */
function addWorkerCpu(result: unknown): unknown {
  const rows = (result as { rows?: unknown } | null)?.rows;
  if (!Array.isArray(rows)) return result;
  let notBefore = 0;
  for (const row of rows as Array<Record<string, unknown>>) {
    if (typeof row.workerCpuSeconds === 'number' || typeof row.seconds !== 'number') continue;
    const found = findTimedInterval(marks, row.seconds, 0.0005 + 1e-7, notBefore);
    if (!found) continue;
    row.workerCpuSeconds = workerCpuSeconds(marks[found[0]]!, marks[found[1]]!);
    row.otherLoadCores = otherLoadCores(marks[found[0]]!, marks[found[1]]!);
    row.workerCpuSecondsFrom = 'bench/pathtracer-child.ts (performance.now marks)';
    notBefore = found[1];
  }
  return result;
}

const mod = (await import(moduleUrl)) as { runPathTracerBenchmark?: () => Promise<unknown> };
if (typeof mod.runPathTracerBenchmark !== 'function') {
  console.error(`${moduleUrl} does not export runPathTracerBenchmark()`);
  process.exit(2);
}
if (mode === '--probe') {
  await emit({ probe: 'ok' });
} else {
  await emit(addWorkerCpu(await mod.runPathTracerBenchmark()));
}
// Dawn can keep the event loop alive after the device is destroyed.
process.exit(0);
