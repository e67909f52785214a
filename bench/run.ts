/**
 * `npm run bench [-- options]`: the BVH build benchmark, the glTF benchmark (load + BVH of a 1M-
 * triangle .glb, samples/s with and without textures; a child process), then the path tracer
 * benchmark of this version beside a baseline git ref (bench/baseline.json), each in its own child
 * processes, alternated round by round. Prints tables and writes every result to bench/results/bench.json.
 * Figures, not pass/fail: a missing or broken baseline only narrows the run to this version.
 * Options and environment knobs: bench/bench-options.ts and bench/README.md.
 */
import { spawnSync } from 'node:child_process';
import { existsSync } from 'node:fs';
import { availableParallelism } from 'node:os';
import { mkdir, readFile, writeFile } from 'node:fs/promises';
import { fileURLToPath } from 'node:url';
import { parseBaselineFile, parseBenchOptions } from './bench-options.ts';
import type { BaselineFile, BenchOptions } from './bench-options.ts';
import { prepareBaselineCheckout } from './baseline-worktree.ts';
import type { BaselineCheckout } from './baseline-worktree.ts';
import { runPathTracerComparison } from './pathtracer-compare.ts';
import type { PathTracerVersion } from './pathtracer-compare.ts';
import type { SceneComparison, Spread, VersionSceneSummary } from './pathtracer-summary.ts';
import { runBvhBenchmark } from './bvh.ts';
import { runNodeChild } from './child-protocol.ts';
import { printGltfResult, type GltfBenchResult } from './gltf.ts';
import { printInstancingResult, type InstancingBenchResult } from './instancing.ts';
import { runRasterBenchmark } from './raster.ts';
import { isCpuAdapter } from './cpu-clock.ts';

const repoRoot = fileURLToPath(new URL('..', import.meta.url)).replace(/\/$/, '');

async function readBaselineFile(): Promise<BaselineFile | null> {
  try {
    return parseBaselineFile(await readFile(new URL('./baseline.json', import.meta.url), 'utf8'));
  } catch (error) {
    console.log(`bench/baseline.json unreadable (${(error as Error).message}); no default baseline`);
    return null;
  }
}

function gitOut(args: string[]): string | null {
  const r = spawnSync('git', args, { cwd: repoRoot, encoding: 'utf8', stdio: ['ignore', 'pipe', 'ignore'] });
  return r.status === 0 ? r.stdout.trim() : null;
}

let options: BenchOptions;
try {
  options = parseBenchOptions(process.argv.slice(2), process.env, await readBaselineFile());
} catch (error) {
  console.error(`bench: ${(error as Error).message}\nusage: npm run bench -- [--baseline <ref> | --no-baseline] [--rounds <n>] [--no-bvh | --bvh-only] [--no-gltf | --gltf-only] [--no-raster | --raster-only] [--no-lighting | --lighting-only] [--no-instancing | --instancing-only] [--output | --output-only] [--no-gpu | --gpu-only] [--browser | --browser-only]`);
  process.exit(2);
}

const results: Record<string, unknown> = {
  date: new Date().toISOString(),
  platform: `${process.platform} ${process.arch}`,
  node: process.version,
  options,
};
const began = performance.now();

if (options.bvh) {
  console.log('BVH build: ours vs three-mesh-bvh');
  const bvh = await runBvhBenchmark();
  results.bvh = bvh;
  console.table(
    bvh.rows.map((r) => ({
      mesh: r.mesh, builder: r.builder, 'build ms (median)': Math.round(r.buildMsMedian), 'min-max': `${Math.round(r.buildMsMin)}-${Math.round(r.buildMsMax)}`,
      runs: r.runs, 'SAH cost': Number(r.sahCost.toFixed(2)), nodes: r.nodeCount, 'GPU ms': r.gpuMsMedian == null ? '' : Number(r.gpuMsMedian.toFixed(2)),
    })),
  );
  console.table(
    bvh.ratios.map((r) => ({
      mesh: r.mesh, ours: r.ours, versus: r.versus, 'time ours/theirs': Number(r.buildTimeRatio.toFixed(2)),
      'speed-up': Number((1 / r.buildTimeRatio).toFixed(2)), 'SAH ours/theirs': Number(r.sahCostRatio.toFixed(3)),
    })),
  );
  console.log(`load average (1 min) before ${bvh.loadAverage.before.toFixed(2)}, after ${bvh.loadAverage.after.toFixed(2)}; parallel cold start ${bvh.parallelColdStartMs.toFixed(0)} ms`);
  if (bvh.gpuAdapter) {
    console.log(`GPU LBVH on ${bvh.gpuAdapter}:`);
    console.table(bvh.gpuVersusCpu.map((g) => ({ mesh: g.mesh, 'SAH GPU/CPU': Number(g.sahCostRatio.toFixed(3)), 'time GPU/CPU (1 thread)': Number(g.buildTimeRatio.toFixed(3)), 'GPU ms': g.gpuMs === null ? '' : Number(g.gpuMs.toFixed(2)) })));
    // The build-time goal (a million triangles rebuilt within a 10 ms frame slice) on an NVIDIA GPU; only a real NVIDIA adapter can say.
    const million = bvh.gpuVersusCpu.find((g) => g.mesh.endsWith(' 1M'));
    const nvidia = /nvidia/i.test(bvh.gpuAdapter);
    console.log(
      million && nvidia
        ? `goal 1M triangles <= 10 ms (NVIDIA): ${million.gpuMs === null ? 'no timestamps' : `${million.gpuMs.toFixed(2)} ms GPU time, ${million.gpuMs <= 10 ? 'met' : 'not met'}`}`
        : 'goal 1M triangles <= 10 ms on an NVIDIA GPU: not measured on this adapter',
    );
  }
} else {
  console.log('BVH build benchmark skipped (--no-bvh / BENCH_BVH=0)');
}

if (options.gltf) {
  console.log('\nglTF: load + BVH of a generated 1M-triangle .glb, samples/s with and without textures (bench/gltf.ts, child process)');
  const outcome = await runNodeChild([fileURLToPath(new URL('./gltf-child.ts', import.meta.url))], repoRoot, Number(process.env.BENCH_CHILD_TIMEOUT_S ?? 1800) * 1000);
  if (outcome.ok) {
    results.gltf = outcome.value;
    printGltfResult(outcome.value as GltfBenchResult);
  } else {
    results.gltf = { error: outcome.error };
    console.log(`  glTF benchmark FAILED: ${outcome.error}`);
    process.exitCode = 1;
  }
} else {
  console.log('glTF benchmark skipped (--no-gltf / BENCH_GLTF=0, or another --x-only)');
}

// Instancing (bench/instancing.ts: forest of EXT_mesh_gpu_instancing placements, flattened vs
// instanced, TLAS updates; a child process): off with --no-instancing / BENCH_INSTANCING=0 or another --x-only.
if (options.instancing) {
  console.log('\nInstancing: two-level acceleration on a generated forest .glb, flattened vs instanced, TLAS updates (bench/instancing.ts, child process)');
  const outcome = await runNodeChild([fileURLToPath(new URL('./instancing-child.ts', import.meta.url))], repoRoot, Number(process.env.BENCH_CHILD_TIMEOUT_S ?? 1800) * 1000);
  if (outcome.ok) {
    results.instancing = outcome.value;
    printInstancingResult(outcome.value as InstancingBenchResult);
  } else {
    results.instancing = { error: outcome.error };
    console.log(`  instancing benchmark FAILED: ${outcome.error}`);
    process.exitCode = 1;
  }
} else {
  console.log('instancing benchmark skipped (--no-instancing / BENCH_INSTANCING=0, or another --x-only)');
}

const fixed = (v: number, digits = 3): string => v.toFixed(digits);
/** Other processes' load (cores) above which the wall-clock figures get a note. */
const BUSY_CORES = 0.2;
const mega = (v: number): string => fixed(v / 1e6);
function range(s: Spread | null): string {
  if (!s) return '';
  const half = ((s.max - s.min) / 2 / s.median) * 100;
  return `${mega(s.min)}–${mega(s.max)} (±${half.toFixed(1)}%)`;
}

function printScene(scene: SceneComparison, names: Record<'baseline' | 'current', string>): void {
  const any = (scene.current ?? scene.baseline)!;
  console.log(`\n${scene.scene}: ${any.resolution ?? '?'}, ${any.spp ?? '?'} spp, ${any.triangles?.toLocaleString('en-US') ?? '?'} triangles`);
  const adapters = [...new Set([scene.baseline?.adapter, scene.current?.adapter].filter((a): a is string => !!a))];
  const cpu = adapters.length > 0 && adapters.every(isCpuAdapter);
  const rows: Record<string, Record<string, string | number>> = {};
  const row = (v: VersionSceneSummary): Record<string, string | number> => ({
    'samples/s (M)': mega(v.samplesPerSecond.median),
    'rays/s (M)': v.raysPerSecond ? mega(v.raysPerSecond.median) : '',
    'samples/s min–max': range(v.samplesPerSecond),
    ...(cpu ? { 'samples/CPU-s (M)': v.samplesPerWorkerCpuSecond ? mega(v.samplesPerWorkerCpuSecond.median) : '', 'samples/CPU-s min–max': range(v.samplesPerWorkerCpuSecond) } : {}),
    'other load (cores)': v.otherLoadCores ? `${fixed(v.otherLoadCores.median, 2)} (max ${fixed(v.otherLoadCores.max, 2)})` : '',
    runs: v.runs,
  });
  if (scene.baseline) rows[names.baseline] = row(scene.baseline);
  if (scene.current) rows[names.current] = row(scene.current);
  if (scene.samplesPerSecondRatio !== null) {
    const perRound = (ratios: number[]): string => (ratios.length ? `rounds: ${ratios.map((r) => fixed(r, 2)).join(' ')}` : '');
    rows['current / baseline'] = {
      'samples/s (M)': fixed(scene.samplesPerSecondRatio),
      'rays/s (M)': scene.raysPerSecondRatio === null ? '' : fixed(scene.raysPerSecondRatio),
      'samples/s min–max': perRound(scene.pairedSamplesPerSecondRatios),
      ...(cpu
        ? {
          'samples/CPU-s (M)': scene.samplesPerWorkerCpuSecondRatio === null ? '' : fixed(scene.samplesPerWorkerCpuSecondRatio),
          'samples/CPU-s min–max': perRound(scene.pairedSamplesPerWorkerCpuSecondRatios),
        }
        : {}),
      'other load (cores)': '',
      runs: scene.pairedSamplesPerSecondRatios.length,
    };
  }
  console.table(rows);
  console.log(`adapter: ${adapters.join(' | ') || 'unknown'}`);
  if (scene.mismatch) console.log(`WARNING: ${scene.mismatch}`);
  const busiest = Math.max(scene.baseline?.otherLoadCores?.max ?? 0, scene.current?.otherLoadCores?.max ?? 0);
  if (busiest > BUSY_CORES) {
    console.log(
      `NOTE: other processes used up to ${fixed(busiest, 2)} cores during timed frames (of ${availableParallelism()}): wall-clock figures are unreliable` +
        (cpu ? '; samples/CPU-s is far less affected' : '') + '.',
    );
  }
}

let currentFailed = false;
if (options.pathTracer && existsSync(new URL('./pathtracer.ts', import.meta.url))) {
  console.log(`\nPath tracer: child processes, versions alternated, ${options.rounds} round(s), BENCH_SPP=${process.env.BENCH_SPP ?? '(default)'}`);
  const versions: PathTracerVersion[] = [];
  let baseline: BaselineCheckout | { ok: false; reason: string } | null = null;
  if (options.baseline.enabled) {
    const { ref, source } = options.baseline;
    console.log(`  baseline: ${ref} (from ${source})`);
    try {
      baseline = await prepareBaselineCheckout(ref, { repoRoot, ...(process.env.BENCH_BASELINE_DIR ? { worktreesDir: process.env.BENCH_BASELINE_DIR } : {}) });
    } catch (error) {
      baseline = { ok: false, ref, reason: `unexpected error: ${(error as Error).stack ?? String(error)}` };
    }
    if (baseline.ok) {
      console.log(`  baseline ${baseline.shortSha} "${baseline.subject}" in ${baseline.dir} (${baseline.reused ? 'reused' : 'new'}, node_modules: ${baseline.modules})`);
      versions.push({ label: 'baseline', name: `baseline ${baseline.shortSha}`, root: baseline.dir });
    } else {
      console.log(`  BASELINE SKIPPED: ${baseline.reason}\n  measuring the current version only`);
    }
  } else {
    console.log(`  baseline off (${options.baseline.reason}): measuring the current version only`);
  }
  const head = gitOut(['rev-parse', '--short', 'HEAD']);
  const dirty = head !== null && gitOut(['status', '--porcelain', '--untracked-files=no']) !== '';
  const currentName = `current ${head ?? ''}${dirty ? '+changes' : ''}`.trim();
  versions.push({ label: 'current', name: currentName, root: repoRoot });

  const childTimeoutMs = Number(process.env.BENCH_CHILD_TIMEOUT_S ?? 1800) * 1000;
  const comparison = await runPathTracerComparison(versions, options.rounds, { childTimeoutMs });
  const names = { baseline: versions.find((v) => v.label === 'baseline')?.name ?? 'baseline', current: currentName };
  for (const scene of comparison.scenes) printScene(scene, names);
  currentFailed = comparison.runs.some((r) => r.version === 'current' && r.error !== undefined);

  results.pathtracer = {
    spp: process.env.BENCH_SPP ?? 'harness default',
    baseline: options.baseline.enabled
      ? { ref: options.baseline.ref, source: options.baseline.source, description: options.baseline.description, checkout: baseline }
      : { off: options.baseline.reason },
    current: { name: currentName, head, uncommittedChanges: dirty },
    ...comparison,
  };
}

// Raster renderer (bench/raster.ts): off with --no-raster / BENCH_RASTER=0 or another --x-only.
if (options.raster) {
  console.log('\nRaster renderer: 4x MSAA, shadow map, prefiltered environment; GPU-skinned characters');
  const raster = await runRasterBenchmark();
  results.raster = raster;
  console.log(`  adapter: ${raster.adapter}`);
  console.table(raster.rows.map((r) => ({ characters: r.characters, size: `${r.width}x${r.height}`, 'frame ms': r.medianFrameMs.toFixed(1), 'skinned vertices/s': Math.round(r.skinnedVerticesPerSecond) })));
}

// Production output (bench/output.ts: adaptive sampling at equal time, denoising): opt in with
// --output / BENCH_OUTPUT=1 or --output-only; it renders converged references and takes minutes.
if (options.output) {
  const { runOutputBenchmark } = await import('./output.ts');
  console.log('\nProduction output: adaptive sampling at equal time, denoising');
  results.output = await runOutputBenchmark();
}

// GPU figures (bench/gpu.ts: the path tracer's defaults on the 1080p cases; scaled down on
// a CPU adapter): off with --no-gpu / BENCH_GPU=0 or another --x-only.
if (options.gpu) {
  const { runGpuBenchmark, printGpuBenchmark } = await import('./gpu.ts');
  results.gpu = await runGpuBenchmark();
  printGpuBenchmark(results.gpu as Awaited<ReturnType<typeof runGpuBenchmark>>);
}

// Lighting figures (bench/lighting.ts: environment importance sampling, many emitters, portals):
// this version only, in this process; off with --no-lighting / BENCH_LIGHTING=0 or another --x-only.
if (options.lighting) {
  const { runLightingBenchmark, printLightingBenchmark } = await import('./lighting.ts');
  results.lighting = await runLightingBenchmark();
  printLightingBenchmark(results.lighting as Awaited<ReturnType<typeof runLightingBenchmark>>);
}

// Browser section (bench/browser.ts: ours beside three-gpu-pathtracer in Chromium): opt in with
// --browser / BENCH_BROWSER=1 or --browser-only; minutes on SwiftShader.
if (options.browser) {
  const { browserBenchOptions, printBrowserBenchmark, runBrowserBenchmark } = await import('./browser.ts');
  console.log('\nBrowser: ours and three-gpu-pathtracer in one Chromium, equal time per scene (bench/browser.ts)');
  const browser = await runBrowserBenchmark(browserBenchOptions(process.env));
  results.browser = browser;
  printBrowserBenchmark(browser);
}

results.totalSeconds = (performance.now() - began) / 1000;
const outDir = new URL('./results/', import.meta.url);
await mkdir(outDir, { recursive: true });
await writeFile(new URL('bench.json', outDir), `${JSON.stringify(results, null, 2)}\n`);
console.log(`\nwrote ${new URL('bench.json', outDir).pathname} (bench took ${Math.round((performance.now() - began) / 1000)} s)`);
if (currentFailed) process.exitCode = 1;
