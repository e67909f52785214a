/**
 * CPU BVH construction benchmark: our binned SAH builder (src/accel/bvh-builder.ts), single-threaded
 * (`buildBvh`) and on workers (`buildBvhParallel`, the path `buildBvhAsync` takes for large meshes),
 * beside three-mesh-bvh's MeshBVH with its SAH and CENTER strategies, on the same deterministic 100k-
 * and 1M-triangle meshes in the same process. Figures, not pass/fail: build time (median, min and max
 * of a few runs) and the SAH cost of each tree under one cost model (C_trav = C_isect = 1,
 * bvh-sah.ts), as ratios.
 *
 * Settings (chosen to be comparable):
 * - ours: maxLeafSize 4 (smaller nodes become leaves), leaf cap 16, 16 bins, depth <= 48, WebAssembly
 *   SIMD loops; parallel: `BVH_BENCH_WORKERS` workers
 *   (default navigator.hardwareConcurrency).
 * - three-mesh-bvh: targetLeafSize 4, maxDepth 48, indirect: true (it permutes an index array, like
 *   our triangleOrder, instead of rewriting the geometry), verbose: false. Its SAH uses 8 bins (or
 *   every centroid in small nodes) and C_isect = 1.25; CENTER splits the longest axis at its middle.
 * - ours, GPU LBVH: `GpuBvhBuilder` (src/accel/gpu-build/) on the WebGPU adapter of this process
 *   (Dawn: lavapipe here, a real GPU elsewhere), 30-bit Morton keys, SAH leaf collapse up to 8. Its
 *   input is the primitive records already on the device (the renderer uploads them anyway), so the
 *   upload is not timed; wall time runs from submission until the tree's figures are read back, GPU
 *   time is the timestamp-query span of the build's compute pass where the adapter has timestamps.
 *   One untimed build per mesh first (scratch allocation).
 * The machine is shared and noisy, so the builders take turns run by run (one run of each, then the
 * next round) and every run's time is kept. Times are wall clock around the whole call (ours
 * includes the final SAH evaluation, ~1% of it). The worker pool is started by an untimed warm-up;
 * its cold start is reported on its own.
 */
import { buildBvh, buildBvhParallel } from '../src/accel/bvh-builder.ts';
import { computeThreeMeshBvhSahCost } from '../src/accel/bvh-sah.ts';
import { GpuBvhBuilder } from '../src/accel/gpu-build/gpu-bvh-builder.ts';
import { packWavefrontTriangles } from '../src/accel/triangle-packing.ts';
import { acquireGpuDevice } from '../src/gpu/acquire-device.ts';
import { BufferUsage } from '../src/gpu/webgpu-constants.ts';
import { bvhNodeLayout, primitiveLayout } from '../src/gpu-layout/records.ts';

export interface BvhBenchRow {
  mesh: string;
  triangles: number;
  builder: string;
  runs: number;
  buildMsMedian: number;
  buildMsMin: number;
  buildMsMax: number;
  buildMsAll: number[];
  sahCost: number;
  nodeCount: number;
  /** GPU builders: GPU time of the build pass (timestamp queries), median over the runs; null without timestamps. */
  gpuMsMedian?: number | null;
}

export interface BvhBenchRatio {
  mesh: string;
  ours: string;
  versus: string;
  /** ours / theirs: < 1 means we build faster. */
  buildTimeRatio: number;
  /** ours / theirs: < 1 means our tree is cheaper to trace under the SAH model. */
  sahCostRatio: number;
}

export interface BvhBenchResult {
  name: 'bvh';
  node: string;
  /** 1-minute load averages before and after (os.loadavg): other work on the machine. */
  loadAverage: { before: number; after: number };
  /** First `buildBvhParallel` call of the process (starting the workers) on the first mesh, ms. */
  parallelColdStartMs: number;
  workers: number;
  threeMeshBvhVersion: string;
  settings: Record<string, unknown>;
  rows: BvhBenchRow[];
  ratios: BvhBenchRatio[];
  /** The WebGPU adapter the GPU builder ran on; null when none was available (no GPU rows). */
  gpuAdapter: string | null;
  /** GPU LBVH against our CPU binned SAH (1 thread) per mesh: SAH ratio (> 1: costlier to trace) and time ratio. */
  gpuVersusCpu: { mesh: string; sahCostRatio: number; buildTimeRatio: number; gpuMs: number | null }[];
  totalMs: number;
}

/** The GPU builder over one mesh: the records uploaded once, a builder with its scratch kept between runs. */
async function gpuBuilder(device: GPUDevice, positions: Float32Array): Promise<{ run: () => Promise<{ sahCost: number; nodeCount: number; gpuMs: number | null }>; destroy: () => void }> {
  const n = positions.length / 9;
  const records = packWavefrontTriangles(positions, Uint32Array.from({ length: n }, (_, i) => i));
  const usage = BufferUsage.STORAGE | BufferUsage.COPY_DST;
  const buffers = {
    source: device.createBuffer({ size: records.byteLength, usage }),
    primitives: device.createBuffer({ size: n * primitiveLayout.size, usage }),
    nodes: device.createBuffer({ size: (2 * n - 1) * bvhNodeLayout.size, usage }),
    parents: device.createBuffer({ size: (2 * n - 1) * 4, usage }),
  };
  device.queue.writeBuffer(buffers.source, 0, records);
  const builder = await GpuBvhBuilder.create(device, { ...buffers, primitiveCount: n });
  await builder.build();
  return {
    run: async () => {
      const r = await builder.build();
      return { sahCost: r.sahCost, nodeCount: r.nodeCount, gpuMs: r.gpuTimeMs };
    },
    destroy: () => {
      builder.destroy();
      for (const b of Object.values(buffers)) b.destroy();
    },
  };
}

/** mulberry32 */
function rng(seed: number): () => number {
  let s = seed | 0;
  return () => {
    s = (s + 0x6d2b79f5) | 0;
    let t = Math.imul(s ^ (s >>> 15), 1 | s);
    t = (t + Math.imul(t ^ (t >>> 7), 61 | t)) ^ t;
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

/**
 * A displaced terrain grid (80% of the triangles: uniform, well-behaved) plus clutter (20%): rocks of
 * widely varying size, long thin "grass blades" and a few large slanted panels spread over and above
 * the terrain, so naive splits straddle big triangles and the SAH has something to win.
 */
export function benchmarkMesh(triangles: number, seed = 1): Float32Array {
  const r = rng(seed);
  const out = new Float32Array(triangles * 9);
  const gridTris = Math.floor(triangles * 0.8);
  const g = Math.floor(Math.sqrt(gridTris / 2));
  const size = 100;
  const h = (x: number, y: number): number =>
    6 * Math.sin(x * 0.05) * Math.cos(y * 0.07) + 2 * Math.sin(x * 0.31 + y * 0.23) + 0.5 * Math.cos(x * 1.7 - y * 1.3);
  let o = 0;
  const put = (x: number, y: number, z: number): void => {
    out[o++] = x;
    out[o++] = y;
    out[o++] = z;
  };
  const cell = size / g;
  for (let j = 0; j < g; j++) {
    for (let i = 0; i < g; i++) {
      const x0 = i * cell, y0 = j * cell, x1 = x0 + cell, y1 = y0 + cell;
      put(x0, y0, h(x0, y0)); put(x1, y0, h(x1, y0)); put(x1, y1, h(x1, y1));
      put(x0, y0, h(x0, y0)); put(x1, y1, h(x1, y1)); put(x0, y1, h(x0, y1));
    }
  }
  const placed = g * g * 2;
  for (let t = placed; t < triangles; t++) {
    const cx = r() * size, cy = r() * size;
    const cz = h(cx, cy) + r() * 20;
    const kind = r();
    // Log-uniform sizes from 1 cm to 10 m; blades are long and thin; 1% are big panels.
    const s = kind < 0.01 ? 10 + r() * 30 : 0.01 * 1000 ** r();
    const stretch = kind > 0.7 ? [0.05, 0.05, 8] : [1, 1, 1];
    for (let v = 0; v < 3; v++) {
      put(cx + (r() - 0.5) * s * stretch[0]!, cy + (r() - 0.5) * s * stretch[1]!, cz + (r() - 0.5) * s * stretch[2]!);
    }
  }
  return out;
}

interface ThreeModule {
  BufferGeometry: new () => { setAttribute(name: string, attribute: unknown): void; dispose(): void };
  BufferAttribute: new (array: Float32Array, itemSize: number) => unknown;
}
interface MeshBvhModule {
  MeshBVH: new (geometry: unknown, options: Record<string, unknown>) => { _roots: ArrayBuffer[] };
  SAH: number;
  CENTER: number;
}

function median(values: number[]): number {
  const s = [...values].sort((a, b) => a - b);
  const m = s.length >> 1;
  return s.length % 2 ? s[m]! : (s[m - 1]! + s[m]!) / 2;
}

type Builder = [name: string, build: () => Promise<{ sahCost: number; nodeCount: number }>];

export async function runBvhBenchmark(options: { sizes?: number[]; runs?: number; log?: (line: string) => void } = {}): Promise<BvhBenchResult> {
  const log = options.log ?? ((line: string) => console.log(line));
  const began = performance.now();
  // Loaded through variables so the type checker does not need three's (absent) type declarations.
  const threeSpec = 'three';
  const bvhSpec = 'three-mesh-bvh';
  const THREE = (await import(threeSpec)) as ThreeModule;
  const TMB = (await import(bvhSpec)) as MeshBvhModule;
  const { readFile } = await import('node:fs/promises');
  const { loadavg } = await import('node:os');
  const tmbPackage = JSON.parse(await readFile(new URL('../node_modules/three-mesh-bvh/package.json', import.meta.url), 'utf8')) as { version: string };
  const envWorkers = Number(process.env.BVH_BENCH_WORKERS);
  const workers = Number.isInteger(envWorkers) && envWorkers > 0 ? envWorkers : Math.max(1, Math.min(8, navigator.hardwareConcurrency || 2));
  const loadBefore = loadavg()[0]!;

  let gpu: { device: GPUDevice; adapter: string } | null = null;
  try {
    const acquired = await acquireGpuDevice();
    gpu = { device: acquired.device, adapter: acquired.adapterDescription };
  } catch (error) {
    log(`  no WebGPU adapter (${(error as Error).message}): GPU builder skipped`);
  }
  const gpuVersusCpu: BvhBenchResult['gpuVersusCpu'] = [];

  const sizes = options.sizes ?? [100_000, 1_000_000];
  const rows: BvhBenchRow[] = [];
  const ratios: BvhBenchRatio[] = [];
  let parallelColdStartMs = NaN;
  for (const triangles of sizes) {
    const positions = benchmarkMesh(triangles);
    const mesh = `terrain+clutter ${triangles >= 1e6 ? `${triangles / 1e6}M` : `${triangles / 1e3}k`}`;
    const runs = options.runs ?? (triangles >= 500_000 ? 5 : 7);
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));

    const onGpu = gpu ? await gpuBuilder(gpu.device, positions) : null;
    const gpuMs: number[] = [];
    const builders: Builder[] = [
      ['ours, 1 thread', async () => {
        const r = buildBvh(positions, { maxLeafSize: 4, binCount: 16 });
        return { sahCost: r.sahCost, nodeCount: r.nodeCount };
      }],
      [`ours, ${workers} workers`, async () => {
        const r = await buildBvhParallel(positions, { maxLeafSize: 4, binCount: 16, workers });
        return { sahCost: r.sahCost, nodeCount: r.nodeCount };
      }],
      ...([['three-mesh-bvh SAH', TMB.SAH], ['three-mesh-bvh CENTER', TMB.CENTER]] as const).map(
        ([name, strategy]): Builder => [name, async () => {
          const bvh = new TMB.MeshBVH(geometry, { strategy, targetLeafSize: 4, maxDepth: 48, indirect: true, verbose: false });
          const root = bvh._roots[0]!;
          return { sahCost: computeThreeMeshBvhSahCost(root), nodeCount: root.byteLength / 32 };
        }],
      ),
      ...(onGpu
        ? [['ours, GPU LBVH', async () => {
          const r = await onGpu.run();
          if (r.gpuMs !== null) gpuMs.push(r.gpuMs);
          return r;
        }] as Builder]
        : []),
    ];
    if (Number.isNaN(parallelColdStartMs)) {
      const t0 = performance.now();
      await builders[1]![1]();
      parallelColdStartMs = performance.now() - t0;
      log(`  ${mesh}: first buildBvhParallel call (starts ${workers} workers): ${parallelColdStartMs.toFixed(0)} ms`);
    }
    // One untimed warm-up per builder (JIT), on the first mesh only.
    if (triangles === sizes[0]) for (const [, build] of builders) await build();
    gpuMs.length = 0;
    const times = builders.map(() => [] as number[]);
    const last = builders.map(() => ({ sahCost: 0, nodeCount: 0 }));
    for (let k = 0; k < runs; k++) {
      for (let b = 0; b < builders.length; b++) {
        const t0 = performance.now();
        last[b] = await builders[b]![1]();
        times[b]!.push(performance.now() - t0);
      }
    }
    builders.forEach(([builder], b) => {
      const all = times[b]!;
      const row: BvhBenchRow = {
        mesh, triangles, builder, runs,
        buildMsMedian: median(all), buildMsMin: Math.min(...all), buildMsMax: Math.max(...all), buildMsAll: all,
        sahCost: last[b]!.sahCost, nodeCount: last[b]!.nodeCount,
        ...(builder.includes('GPU') ? { gpuMsMedian: gpuMs.length > 0 ? median(gpuMs) : null } : {}),
      };
      rows.push(row);
      const gpuTime = row.gpuMsMedian != null ? `  GPU ${row.gpuMsMedian.toFixed(1)} ms` : '';
      log(`  ${mesh}: ${builder.padEnd(22)} ${row.buildMsMedian.toFixed(0).padStart(6)} ms median of ${runs} (${row.buildMsMin.toFixed(0)}-${row.buildMsMax.toFixed(0)})  SAH ${row.sahCost.toFixed(2)}  nodes ${row.nodeCount}${gpuTime}`);
    });
    geometry.dispose();
    onGpu?.destroy();
    const gpuRow = rows.find((r) => r.mesh === mesh && r.builder === 'ours, GPU LBVH');
    const cpuRow = rows.find((r) => r.mesh === mesh && r.builder === 'ours, 1 thread')!;
    if (gpuRow) {
      gpuVersusCpu.push({ mesh, sahCostRatio: gpuRow.sahCost / cpuRow.sahCost, buildTimeRatio: gpuRow.buildMsMedian / cpuRow.buildMsMedian, gpuMs: gpuRow.gpuMsMedian ?? null });
      log(`  ${mesh}: GPU LBVH / CPU binned SAH: SAH x${(gpuRow.sahCost / cpuRow.sahCost).toFixed(3)}, build time x${(gpuRow.buildMsMedian / cpuRow.buildMsMedian).toFixed(2)} (${gpu!.adapter})`);
    }
    for (const ours of rows.filter((r) => r.mesh === mesh && r.builder.startsWith('ours'))) {
      for (const theirs of rows.filter((r) => r.mesh === mesh && !r.builder.startsWith('ours'))) {
        ratios.push({ mesh, ours: ours.builder, versus: theirs.builder, buildTimeRatio: ours.buildMsMedian / theirs.buildMsMedian, sahCostRatio: ours.sahCost / theirs.sahCost });
      }
    }
  }
  gpu?.device.destroy();
  return {
    name: 'bvh',
    node: process.version,
    loadAverage: { before: loadBefore, after: loadavg()[0]! },
    parallelColdStartMs,
    workers,
    threeMeshBvhVersion: tmbPackage.version,
    settings: {
      costModel: 'C_trav = 1, C_isect = 1, surface areas relative to the root',
      ours: { maxLeafSize: 4, leafSizeCap: 16, binCount: 16, maxDepth: 48, workers, wasm: true },
      threeMeshBvh: { targetLeafSize: 4, maxDepth: 48, indirect: true },
      gpuLbvh: { mortonBits: 30, maxLeafSize: 8, adapter: gpu?.adapter ?? null, timing: 'records on the device; wall = submit to figures read back; GPU = timestamp span of the build pass' },
      timing: 'wall clock per build, builders interleaved run by run; median (min-max) of 7 runs (100k, after one warm-up) or 5 runs (1M)',
    },
    rows,
    ratios,
    gpuAdapter: gpu?.adapter ?? null,
    gpuVersusCpu,
    totalMs: performance.now() - began,
  };
}
