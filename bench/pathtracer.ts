/**
 * Path tracer throughput: samples/s and rays/s on the Cornell box at 512x512 and on a scene of more
 * than 1M triangles (a finely tessellated sphere inside the box), naming the adapter. The first frame
 * of each scene warms up pipelines (shader JIT on software drivers) and is not counted.
 * BENCH_SPP overrides the measured samples per pixel.
 *
 * bench/run.ts runs this file in a child process per version (pathtracer-child.ts), the baseline's
 * own copy for the baseline, and matches scenes by name: keep the scene names and the workload
 * (scenes, size, maxDepth, spp) as they are, or the comparison with older versions is void.
 */
import { createWavefrontPathTracingComputeRenderer } from '../src/pathtracer/index.ts';
import { createCornellBoxScene } from '../src/scene/cornell-box.ts';
import type { WavefrontMeshInput } from '../src/scene/types.ts';
import { cpuMark, otherLoadCores, workerCpuSeconds } from './cpu-clock.ts';

export interface PathTracerBenchRow {
  scene: string;
  triangles: number;
  resolution: string;
  spp: number;
  /** Wall clock of the timed renderFrame. */
  seconds: number;
  samplesPerSecond: number;
  raysPerSecond: number;
  rays: number;
  gpuMs: number | null;
  /** CPU seconds of the threads other than the main one during the timed frame (cpu-clock.ts). */
  workerCpuSeconds: number;
  /** Cores' worth of CPU other processes used during the timed frame (cpu-clock.ts); null off Linux. */
  otherLoadCores: number | null;
  /** Renderer creation: scene preparation, BVH build, pipelines. */
  setupSeconds: number;
  adapter: string;
}

/** Icosphere with `subdivisions` levels: 20 * 4^s triangles. */
export function icosphere(radius: number, center: readonly number[], subdivisions: number): WavefrontMeshInput {
  const t = (1 + Math.sqrt(5)) / 2;
  const verts: number[] = [];
  const push = (x: number, y: number, z: number): number => {
    const l = Math.hypot(x, y, z);
    verts.push(x / l, y / l, z / l);
    return verts.length / 3 - 1;
  };
  for (const v of [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t], [0, -1, -t], [0, 1, -t], [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]]) push(v[0]!, v[1]!, v[2]!);
  let faces = new Uint32Array([0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1]);
  for (let s = 0; s < subdivisions; s++) {
    const cache = new Map<number, number>();
    const mid = (a: number, b: number): number => {
      const key = a < b ? a * 4194304 + b : b * 4194304 + a;
      let m = cache.get(key);
      if (m === undefined) {
        m = push(verts[3 * a]! + verts[3 * b]!, verts[3 * a + 1]! + verts[3 * b + 1]!, verts[3 * a + 2]! + verts[3 * b + 2]!);
        cache.set(key, m);
      }
      return m;
    };
    const next = new Uint32Array(faces.length * 4);
    for (let f = 0; f < faces.length; f += 3) {
      const a = faces[f]!, b = faces[f + 1]!, c = faces[f + 2]!;
      const ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      next.set([a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca], f * 4);
    }
    faces = next;
  }
  const positions = new Float32Array(verts.length);
  const normals = new Float32Array(verts.length);
  for (let i = 0; i < verts.length; i += 3) {
    // A gentle displacement so the surface is not a perfect sphere (SAH has real work to do).
    const d = 1 + 0.04 * Math.sin(9 * verts[i]!) * Math.sin(11 * verts[i + 1]!) * Math.sin(7 * verts[i + 2]!);
    for (let c = 0; c < 3; c++) {
      positions[i + c] = center[c]! + radius * d * verts[i + c]!;
      normals[i + c] = verts[i + c]!;
    }
  }
  return { positions, indices: faces, normals, material: { baseColorFactor: [0.9, 0.75, 0.3, 1], metallicFactor: 1, roughnessFactor: 0.35 } };
}

async function measure(scene: string, meshes: WavefrontMeshInput[], width: number, height: number, spp: number): Promise<PathTracerBenchRow> {
  const cornell = createCornellBoxScene();
  const started = performance.now();
  const renderer = await createWavefrontPathTracingComputeRenderer({
    width, height, maxDepth: 8, samplesPerPixel: 1, meshes, ...(cornell.camera ? { camera: cornell.camera } : {}),
  });
  const setupSeconds = (performance.now() - started) / 1000;
  try {
    await renderer.renderFrame({ samplesPerPixel: 1 }); // warm-up
    const cpu0 = cpuMark();
    const t0 = performance.now();
    const stats = await renderer.renderFrame({ samplesPerPixel: spp });
    const seconds = (performance.now() - t0) / 1000;
    const cpu1 = cpuMark();
    const snapshot = renderer.getSnapshot();
    return {
      scene,
      triangles: snapshot.triangleCount,
      resolution: `${width}x${height}`,
      spp,
      seconds,
      samplesPerSecond: (width * height * spp) / seconds,
      raysPerSecond: stats.rays.total / seconds,
      rays: stats.rays.total,
      gpuMs: stats.gpuTimeMs,
      workerCpuSeconds: workerCpuSeconds(cpu0, cpu1),
      otherLoadCores: otherLoadCores(cpu0, cpu1),
      setupSeconds,
      adapter: snapshot.adapter,
    };
  } finally {
    renderer.destroy();
  }
}

export async function runPathTracerBenchmark(): Promise<{ rows: PathTracerBenchRow[] }> {
  const spp = Number(process.env.BENCH_SPP ?? 8);
  const cornell = createCornellBoxScene().meshes ?? [];
  const rows = [await measure('Cornell box', cornell, 512, 512, spp)];
  // 20 * 4^8 = 1,310,720 triangles.
  const dense = icosphere(0.35, [0.35, -0.6, 0.2], 8);
  rows.push(await measure('Cornell box + 1.3M-triangle sphere', [...cornell, dense], 512, 512, Math.max(1, Math.round(spp / 2))));
  return { rows };
}
