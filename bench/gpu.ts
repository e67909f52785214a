/**
 * GPU figures of the path tracer with its defaults (no tileSize), the same code on any adapter
 * (`npm run bench -- --gpu-only`, or `node bench/gpu.ts`): the workloads a production renderer must
 * sustain (a 1080p still, a 1080p realtime loop, a million-triangle mesh).
 *
 * - Cornell box 1920x1080, 32 spp in one renderFrame, maxDepth 8;
 * - the realtime loop: 1920x1080, 1 spp per renderFrame, maxDepth 8, 30 frames, each frame
 *   requested before the previous one's statistics are awaited (two in flight);
 * - the Cornell box with a 1.3M-triangle sphere, 1920x1080, 16 spp, maxDepth 8 and maxDepth 1.
 *
 * Per case: samples/s and rays/s by ray type (wall clock of the timed frames), ms per frame, GPU ms
 * per frame from timestamp queries and the GPU's busy share of the wall time, dispatches, waves and
 * paths per wave, and the modelled bytes of path state per path per bounce (path-traffic.ts).
 * Every case runs with both integrators, the wavefront (default) and the megakernel, on the same
 * device, and the table gives the megakernel's throughput over the wavefront's per case.
 *
 * A CPU adapter (lavapipe) cannot render these workloads in bench time: there the cases keep their
 * resolution and depth but take 1/16 of the samples (at least 1) and 3 loop frames, and the table
 * says so; BENCH_GPU_SCALE=1 forces the full workload, BENCH_GPU_SCALE=<s> any other fraction.
 */
import { acquireGpuDevice } from '../src/gpu/acquire-device.ts';
import { createWavefrontPathTracingComputeRenderer, pathTracingIntegrators } from '../src/pathtracer/index.ts';
import type { PathTracingIntegrator, WavefrontFrameStats, WavefrontPathTracingRenderer } from '../src/pathtracer/types.ts';
import { pathRecordLayout } from '../src/gpu-layout/records.ts';
import { createCornellBoxScene } from '../src/scene/cornell-box.ts';
import type { WavefrontMeshInput } from '../src/scene/types.ts';
import { isCpuAdapter } from './cpu-clock.ts';
import { pathTrafficPerBounce, unfusedPathTrafficPerBounce } from './path-traffic.ts';
import { icosphere } from './pathtracer.ts';

export interface GpuBenchRow {
  case: string;
  integrator: PathTracingIntegrator;
  width: number;
  height: number;
  /** Samples per pixel of each timed frame. */
  spp: number;
  maxDepth: number;
  /** Timed frames (1, or the loop's). */
  frames: number;
  samplesPerSecond: number;
  raysPerSecond: { camera: number; extension: number; shadow: number; total: number };
  msPerFrame: number;
  /** Timestamp-query GPU time per frame; null without timestamp queries. */
  gpuMsPerFrame: number | null;
  /** GPU time over wall time. */
  gpuBusyShare: number | null;
  dispatchesPerFrame: number;
  wavesPerFrame: number;
  pathsPerWave: number;
  createSeconds: number;
}

export interface GpuBenchmark {
  adapter: string;
  /** Fraction of the full workload's samples (and loop frames) rendered; 1 = the full workload. */
  scale: number;
  pathRecordBytes: number;
  /** Modelled bytes of path state per path per bounce, this version and the five-kernel wavefront before it. */
  bytesPerPathBounce: { fused: number; unfused: number; kernels: Record<string, number> };
  rows: GpuBenchRow[];
}

interface Case {
  name: string;
  meshes: () => WavefrontMeshInput[];
  spp: number;
  maxDepth: number;
  /** Frames of a realtime loop (1 spp each); 0: one offline frame of `spp`. */
  loopFrames: number;
}

const cornell = (): WavefrontMeshInput[] => createCornellBoxScene().meshes ?? [];
// 20 * 4^8 = 1,310,720 triangles: the path tracer benchmark's sphere.
const withSphere = (): WavefrontMeshInput[] => [...cornell(), icosphere(0.35, [0.35, -0.6, 0.2], 8)];

const cases: Case[] = [
  { name: 'Cornell box', meshes: cornell, spp: 32, maxDepth: 8, loopFrames: 0 },
  { name: 'realtime loop (Cornell box)', meshes: cornell, spp: 1, maxDepth: 8, loopFrames: 30 },
  { name: 'Cornell box + 1.3M-triangle sphere', meshes: withSphere, spp: 16, maxDepth: 8, loopFrames: 0 },
  { name: 'Cornell box + 1.3M-triangle sphere', meshes: withSphere, spp: 16, maxDepth: 1, loopFrames: 0 },
];

const WIDTH = 1920;
const HEIGHT = 1080;

function sum(stats: WavefrontFrameStats[], pick: (s: WavefrontFrameStats) => number): number {
  return stats.reduce((n, s) => n + pick(s), 0);
}

async function timeCase(device: GPUDevice, c: Case, scale: number, integrator: PathTracingIntegrator): Promise<GpuBenchRow> {
  const scene = createCornellBoxScene();
  const spp = c.loopFrames > 0 ? 1 : Math.max(1, Math.round(c.spp * scale));
  const frames = c.loopFrames > 0 ? Math.max(3, Math.round(c.loopFrames * scale)) : 1;
  const started = performance.now();
  const renderer: WavefrontPathTracingRenderer = await createWavefrontPathTracingComputeRenderer({
    device, width: WIDTH, height: HEIGHT, maxDepth: c.maxDepth, samplesPerPixel: spp, integrator, meshes: c.meshes(), ...(scene.camera ? { camera: scene.camera } : {}),
  });
  const createSeconds = (performance.now() - started) / 1000;
  try {
    // Warm-up: pipelines, the wave buffers at their size, the driver's first-use work.
    await renderer.renderFrame();
    const stats: WavefrontFrameStats[] = [];
    const t0 = performance.now();
    if (c.loopFrames > 0) {
      // The realtime pattern: request frame k + 1 before awaiting frame k's statistics.
      let previous: Promise<WavefrontFrameStats> | null = null;
      for (let k = 0; k < frames; k++) {
        const next = renderer.renderFrame();
        if (previous) stats.push(await previous);
        previous = next;
      }
      stats.push(await previous!);
    } else {
      stats.push(await renderer.renderFrame());
    }
    const seconds = (performance.now() - t0) / 1000;
    const gpuMs = stats.every((s) => s.gpuTimeMs !== null) ? sum(stats, (s) => s.gpuTimeMs!) : null;
    const last = stats.at(-1)!;
    return {
      case: c.name,
      // The form that ran: a device with too few storage buffers per stage runs the wavefront for a megakernel request.
      integrator: renderer.getSnapshot().integrator,
      width: WIDTH,
      height: HEIGHT,
      spp,
      maxDepth: c.maxDepth,
      frames,
      samplesPerSecond: (WIDTH * HEIGHT * spp * frames) / seconds,
      raysPerSecond: {
        camera: sum(stats, (s) => s.rays.camera) / seconds,
        extension: sum(stats, (s) => s.rays.extension) / seconds,
        shadow: sum(stats, (s) => s.rays.shadow) / seconds,
        total: sum(stats, (s) => s.rays.total) / seconds,
      },
      msPerFrame: (seconds * 1000) / frames,
      gpuMsPerFrame: gpuMs === null ? null : gpuMs / frames,
      gpuBusyShare: gpuMs === null ? null : gpuMs / (seconds * 1000),
      dispatchesPerFrame: last.gpuParallelism.directDispatches + last.gpuParallelism.indirectDispatches,
      wavesPerFrame: last.waves,
      pathsPerWave: last.wavePaths,
      createSeconds,
    };
  } finally {
    renderer.destroy();
  }
}

export async function runGpuBenchmark(): Promise<GpuBenchmark> {
  const acquired = await acquireGpuDevice();
  try {
    const software = acquired.softwareAdapter || isCpuAdapter(acquired.adapterDescription);
    const scale = process.env.BENCH_GPU_SCALE !== undefined ? Number(process.env.BENCH_GPU_SCALE) : software ? 1 / 16 : 1;
    if (!(scale > 0 && scale <= 1)) throw new Error(`BENCH_GPU_SCALE: expected a number in (0, 1], got ${process.env.BENCH_GPU_SCALE}`);
    const rows: GpuBenchRow[] = [];
    for (const c of cases) for (const integrator of pathTracingIntegrators) rows.push(await timeCase(acquired.device, c, scale, integrator));
    const fused = pathTrafficPerBounce();
    return {
      adapter: acquired.adapterDescription,
      scale,
      pathRecordBytes: pathRecordLayout.size,
      bytesPerPathBounce: { fused: fused.total, unfused: unfusedPathTrafficPerBounce().total, kernels: fused.kernels },
      rows,
    };
  } finally {
    acquired.device.destroy();
  }
}

const fixed = (v: number, digits: number): number => Number(v.toFixed(digits));

/** The wavefront row of the same case as rows[i] (the rows of a case are adjacent, wavefront first). */
function wavefrontRow(rows: readonly GpuBenchRow[], i: number): GpuBenchRow {
  for (let j = i; j >= 0; j--) if (rows[j]!.integrator === 'wavefront') return rows[j]!;
  throw new Error(`no wavefront row before row ${i}`);
}

export function printGpuBenchmark(b: GpuBenchmark): void {
  const note = b.scale === 1 ? 'full workload' : `scaled: ${fixed(b.scale, 4)} of the samples and loop frames (BENCH_GPU_SCALE=1 for the full workload)`;
  console.log(`\nGPU: path tracer defaults (no tileSize), ${note}; adapter ${b.adapter}`);
  console.table(
    b.rows.map((r, i) => ({
      case: r.case,
      integrator: r.integrator,
      size: `${r.width}x${r.height}`,
      spp: r.spp,
      depth: r.maxDepth,
      frames: r.frames,
      'Msamples/s': fixed(r.samplesPerSecond / 1e6, 3),
      'Mrays/s camera': fixed(r.raysPerSecond.camera / 1e6, 3),
      'Mrays/s extension': fixed(r.raysPerSecond.extension / 1e6, 3),
      'Mrays/s shadow': fixed(r.raysPerSecond.shadow / 1e6, 3),
      'ms/frame': fixed(r.msPerFrame, 1),
      'GPU ms/frame': r.gpuMsPerFrame === null ? '' : fixed(r.gpuMsPerFrame, 1),
      'GPU busy': r.gpuBusyShare === null ? '' : `${Math.round(r.gpuBusyShare * 100)}%`,
      dispatches: r.dispatchesPerFrame,
      waves: r.wavesPerFrame,
      'paths/wave': r.pathsPerWave,
      // Renderer creation: BVH build, upload, and the kernels' compilation the first time a feature set and integrator appear.
      'create s': fixed(r.createSeconds, 1),
      'vs wavefront': r.integrator === 'wavefront' ? '' : `${fixed(r.samplesPerSecond / wavefrontRow(b.rows, i).samplesPerSecond, 2)}x`,
    })),
  );
  console.log(
    `path record ${b.pathRecordBytes} B; modelled path-state traffic per path per bounce ${b.bytesPerPathBounce.fused} B ` +
      `(${Object.entries(b.bytesPerPathBounce.kernels).map(([k, v]) => `${k} ${v}`).join(', ')}) against ${b.bytesPerPathBounce.unfused} B for the five-kernel wavefront`,
  );
}

if (import.meta.url === `file://${process.argv[1]}`) {
  printGpuBenchmark(await runGpuBenchmark());
  // Dawn can keep the event loop alive after the device is destroyed.
  process.exit(0);
}
