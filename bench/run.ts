/**
 * `npm run bench`: the BVH build benchmark, then the path tracer benchmark when bench/pathtracer.ts
 * exists. Prints tables and writes every result to bench/results/bench.json. Figures, not pass/fail.
 * `BENCH_ONLY=bvh npm run bench` runs the BVH part alone (results in bench/results/bench-bvh.json).
 */
import { existsSync } from 'node:fs';
import { mkdir, writeFile } from 'node:fs/promises';
import { runBvhBenchmark } from './bvh.ts';

const results: Record<string, unknown> = { date: new Date().toISOString(), platform: `${process.platform} ${process.arch}`, node: process.version };

console.log('BVH build: ours vs three-mesh-bvh');
const bvh = await runBvhBenchmark();
results.bvh = bvh;
console.table(
  bvh.rows.map((r) => ({
    mesh: r.mesh, builder: r.builder, 'build ms (median)': Math.round(r.buildMsMedian), 'min-max': `${Math.round(r.buildMsMin)}-${Math.round(r.buildMsMax)}`,
    runs: r.runs, 'SAH cost': Number(r.sahCost.toFixed(2)), nodes: r.nodeCount,
  })),
);
console.table(
  bvh.ratios.map((r) => ({ mesh: r.mesh, ours: r.ours, versus: r.versus, 'time ours/theirs': Number(r.buildTimeRatio.toFixed(2)), 'speed-up': Number((1 / r.buildTimeRatio).toFixed(2)), 'SAH ours/theirs': Number(r.sahCostRatio.toFixed(3)) })),
);
console.log(`load average (1 min) before ${bvh.loadAverage.before.toFixed(2)}, after ${bvh.loadAverage.after.toFixed(2)}; parallel cold start ${bvh.parallelColdStartMs.toFixed(0)} ms`);

const bvhOnly = process.env.BENCH_ONLY === 'bvh';
const pathTracerModule = new URL('./pathtracer.ts', import.meta.url);
if (!bvhOnly && existsSync(pathTracerModule)) {
  console.log('Path tracer');
  const mod = (await import(pathTracerModule.href)) as { runPathTracerBenchmark?: () => Promise<unknown> };
  if (typeof mod.runPathTracerBenchmark === 'function') {
    const pt = await mod.runPathTracerBenchmark();
    results.pathtracer = pt;
    const rows = (pt as { rows?: unknown }).rows;
    if (Array.isArray(rows)) console.table(rows);
    else console.log(JSON.stringify(pt, null, 2));
  }
}

const outDir = new URL('./results/', import.meta.url);
await mkdir(outDir, { recursive: true });
const outFile = new URL(bvhOnly ? 'bench-bvh.json' : 'bench.json', outDir);
await writeFile(outFile, `${JSON.stringify(results, null, 2)}\n`);
console.log(`wrote ${outFile.pathname}`);
