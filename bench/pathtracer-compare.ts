/**
 * Runs each version's runPathTracerBenchmark() in child Node processes (one WebGPU device each),
 * alternating versions round by round (baseline, current, baseline, current, ...) so that drift of a
 * shared machine's load falls on both, then summarises per scene (pathtracer-summary.ts).
 */
import { join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { runNodeChild } from './child-protocol.ts';
import { readPathTracerResult, summarizeRuns } from './pathtracer-summary.ts';
import type { PathTracerRun, SceneComparison, VersionLabel } from './pathtracer-summary.ts';

export interface PathTracerVersion {
  label: VersionLabel;
  /** For the log, e.g. "baseline ca1bff9". */
  name: string;
  /** Checkout root: the child runs `<root>/bench/pathtracer.ts` with this working directory. */
  root: string;
}

export interface PathTracerComparison {
  rounds: number;
  schedule: string[];
  runs: PathTracerRun[];
  scenes: SceneComparison[];
}

const CHILD_SCRIPT = fileURLToPath(new URL('./pathtracer-child.ts', import.meta.url));

export async function runPathTracerComparison(
  versions: readonly PathTracerVersion[],
  rounds: number,
  options: { childTimeoutMs: number; log?: (line: string) => void },
): Promise<PathTracerComparison> {
  const log = options.log ?? ((line: string) => console.log(line));
  const runs: PathTracerRun[] = [];
  const schedule: string[] = [];
  const failed = new Set<VersionLabel>();
  for (let round = 1; round <= rounds; round++) {
    for (const version of versions) {
      // A version that failed once is not retried: a broken harness would cost a full run each round.
      if (failed.has(version.label)) continue;
      schedule.push(`${round}:${version.label}`);
      const harness = pathToFileURL(join(version.root, 'bench', 'pathtracer.ts')).href;
      const outcome = await runNodeChild([CHILD_SCRIPT, harness], version.root, options.childTimeoutMs);
      const prefix = `  round ${round}/${rounds} ${version.name.padEnd(20)} ${outcome.seconds.toFixed(0).padStart(4)} s`;
      let run: PathTracerRun;
      if (outcome.ok) {
        try {
          run = { version: version.label, round, childSeconds: outcome.seconds, scenes: readPathTracerResult(outcome.value) };
        } catch (error) {
          run = { version: version.label, round, childSeconds: outcome.seconds, scenes: [], error: (error as Error).message };
        }
      } else {
        run = { version: version.label, round, childSeconds: outcome.seconds, scenes: [], error: outcome.error };
      }
      runs.push(run);
      if (run.error !== undefined) {
        failed.add(version.label);
        log(`${prefix}  FAILED: ${run.error}`);
      } else {
        log(`${prefix}  ${run.scenes.map((s) => `${s.scene}: ${(s.samplesPerSecond / 1e6).toFixed(3)} M samples/s${s.samplesPerWorkerCpuSecond === null ? '' : ` (${(s.samplesPerWorkerCpuSecond / 1e6).toFixed(3)} M per CPU-s)`}`).join(' | ')}`);
      }
    }
  }
  return { rounds, schedule, runs, scenes: summarizeRuns(runs) };
}
