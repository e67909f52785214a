/**
 * `npm run bench`: the BVH build benchmark, then the path tracer benchmark when bench/pathtracer.ts
 * exists. Prints tables and writes every result to bench/results/bench.json. Figures, not pass/fail.
 */
import { existsSync } from 'node:fs';
import { mkdir, writeFile } from 'node:fs/promises';
import { runBvhBenchmark } from './bvh.ts';

const results: Record<string, unknown> = { date: new Date().toISOString(), platform: `${process.platform} ${process.arch}`, node: process.version };

console.log('BVH build: ours vs three-mesh-bvh');
const bvh = await runBvhBenchmark();
results.bvh = bvh;
console.table(
  bvh.rows.map((r) => ({ mesh: r.mesh, builder: r.builder, 'build ms (median)': Math.round(r.buildMsMedian), runs: r.runs, 'SAH cost': Number(r.sahCost.toFixed(2)), nodes: r.nodeCount })),
);
console.table(
  bvh.ratios.map((r) => ({ mesh: r.mesh, 'ours / theirs': r.versus, 'build time': Number(r.buildTimeRatio.toFixed(2)), 'SAH cost': Number(r.sahCostRatio.toFixed(3)) })),
);

const pathTracerModule = new URL('./pathtracer.ts', import.meta.url);
if (existsSync(pathTracerModule)) {
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
await writeFile(new URL('bench.json', outDir), `${JSON.stringify(results, null, 2)}\n`);
console.log(`wrote ${new URL('bench.json', outDir).pathname}`);
