/**
 * Lighting figures (`npm run bench`, or `node bench/lighting.ts` alone): what the samplers buy, as
 * per-pixel variance at equal samples and at equal time.
 *
 * - Environment importance sampling: a diffuse sphere and floor under an HDRI whose small sun (4
 *   texels of 2048) is 5000 times brighter than the sky, sampled in proportion to luminance x
 *   sin(theta) against uniform directions (`environmentSampling: 'uniform'`).
 * - Many emitters: a floor under 10,000 small emissive triangles against the same power in 8
 *   triangles; the 10,000 picked by the light tree (`lightSampler: 'auto'`) and by the power alias
 *   table (`'power'`).
 * - Portals: a room lit by an HDRI through a window, with and without a portal on the window.
 *
 * Variance: two renders with different seeds a, b give sum (a - b)^2 / 2 per pixel, an unbiased
 * estimate of the variance of one render's pixel; reported relative to the squared image mean.
 * Time: renderFrame with the pipelines already built (a warm-up frame first): on a CPU adapter
 * (lavapipe) the CPU seconds of the driver's threads (cpu-clock.ts; far steadier than wall clock
 * on a shared machine), else wall clock. Equal-time gain = (variance x time) of the baseline over
 * that of the method.
 */
import { acquireGpuDevice } from '../src/gpu/acquire-device.ts';
import { cpuMark, isCpuAdapter, workerCpuSeconds } from './cpu-clock.ts';
import { createWavefrontPathTracingComputeRenderer } from '../src/pathtracer/index.ts';
import type { WavefrontPathTracingOptions } from '../src/pathtracer/types.ts';
import type { WavefrontMaterialInput, WavefrontMeshInput } from '../src/scene/types.ts';
import { rng } from '../test/helpers/random.ts';
import { windowPortal, windowRoomMesh } from '../test/helpers/window-room.ts';

export interface LightingMeasurement {
  scene: string;
  method: string;
  spp: number;
  /** Mean over pixels of the per-pixel variance of one render, over the squared image mean. */
  relativeVariance: number;
  /** Wall-clock ms of one renderFrame at `spp` (pipelines warm). */
  frameMs: number;
  /** CPU ms of the driver's threads during that frame (the work, on a CPU adapter). */
  frameCpuMs: number;
  /** ms to create the renderer (validation, BVH, lights heap and tree, pipelines). */
  createMs: number;
}

export interface LightingComparison {
  scene: string;
  baseline: string;
  method: string;
  /** Variance ratio at equal samples (baseline / method). */
  equalSamples: number;
  /** (variance x time) ratio: the gain at equal time. */
  equalTime: number;
}

export interface LightingBenchmark {
  adapter: string;
  /** Which time the equal-time gains use. */
  time: 'worker CPU' | 'wall clock';
  size: number;
  measurements: LightingMeasurement[];
  comparisons: LightingComparison[];
}

const SIZE = Number(process.env.BENCH_LIGHTING_SIZE ?? 48);
const SPP = Number(process.env.BENCH_LIGHTING_SPP ?? 32);

const lambert = (c: number): WavefrontMaterialInput => ({ baseColorFactor: [c, c, c, 1], metallicFactor: 0, roughnessFactor: 1, ior: 1 });
const floor = (half: number): WavefrontMeshInput => ({ positions: [-half, 0, -half, half, 0, -half, half, 0, half, -half, 0, half], indices: [0, 2, 1, 0, 3, 2], material: lambert(0.6) });

/** An HDRI with a dim sky and a 2 x 2 texel sun of `sun` radiance (64 x 32 texels). */
function sunnyMap(sun: number): { width: number; height: number; data: Float32Array } {
  const width = 64;
  const height = 32;
  const data = new Float32Array(width * height * 4);
  for (let j = 0; j < height; j++) {
    for (let i = 0; i < width; i++) {
      const v = (j + 0.5) / height;
      const sky = v < 0.5 ? [0.3 + 0.4 * (1 - 2 * v), 0.4 + 0.3 * (1 - 2 * v), 0.6] : [0.1, 0.09, 0.08];
      const isSun = i >= 40 && i < 42 && j >= 8 && j < 10;
      data.set(isSun ? [sun, 0.95 * sun, 0.85 * sun, 1] : [...sky, 1], 4 * (j * width + i));
    }
  }
  return { width, height, data };
}

/** `count` triangles in the slab y in [1.5, 2], |x|, |z| <= 2.5, facing down-ish, total emitted power fixed. */
function emitters(count: number, seed: number, totalRadianceArea: number): WavefrontMeshInput {
  const random = rng(seed);
  const positions: number[] = [];
  const edge = Math.sqrt((2 * totalRadianceArea) / count);
  for (let t = 0; t < count; t++) {
    const c = [5 * random() - 2.5, 1.5 + 0.5 * random(), 5 * random() - 2.5];
    // A right triangle of legs `edge` in the xz plane, wound to face -y, tilted a little.
    const tilt = 0.3 * (random() - 0.5);
    positions.push(c[0]!, c[1]!, c[2]!, c[0]! + edge, c[1]!, c[2]!, c[0]!, c[1]! + tilt * edge, c[2]! + edge);
  }
  return { positions, material: { baseColorFactor: [0, 0, 0, 1], emissiveFactor: [1, 0.9, 0.75], emissiveStrength: 20, doubleSided: false } };
}

async function measure(device: GPUDevice, scene: string, method: string, options: Partial<WavefrontPathTracingOptions>): Promise<LightingMeasurement> {
  const images: Float32Array[] = [];
  let frameMs = 0;
  let frameCpuMs = 0;
  let createMs = 0;
  for (const seed of [1, 2]) {
    const t0 = performance.now();
    const renderer = await createWavefrontPathTracingComputeRenderer({ device, width: SIZE, height: SIZE, maxDepth: 4, seed, ...options } as WavefrontPathTracingOptions);
    createMs += (performance.now() - t0) / 2;
    try {
      await renderer.renderFrame({ samplesPerPixel: 1 });
      await renderer.readRadiance();
      const mark = cpuMark();
      const t1 = performance.now();
      await renderer.renderFrame({ samplesPerPixel: SPP });
      frameMs += (performance.now() - t1) / 2;
      frameCpuMs += (workerCpuSeconds(mark, cpuMark()) * 1000) / 2;
      images.push((await renderer.readRadiance()).data);
    } finally {
      renderer.destroy();
    }
  }
  let diff = 0;
  let mean = 0;
  const [a, b] = images as [Float32Array, Float32Array];
  for (let k = 0; k < SIZE * SIZE; k++) {
    for (let c = 0; c < 3; c++) {
      diff += (a[4 * k + c]! - b[4 * k + c]!) ** 2 / 2;
      mean += (a[4 * k + c]! + b[4 * k + c]!) / 2;
    }
  }
  const n = 3 * SIZE * SIZE;
  mean /= n;
  return { scene, method, spp: SPP + 1, relativeVariance: diff / n / (mean * mean), frameMs, frameCpuMs, createMs };
}

function compare(rows: LightingMeasurement[], scene: string, baseline: string, method: string, cpu: boolean): LightingComparison {
  const b = rows.find((r) => r.scene === scene && r.method === baseline)!;
  const m = rows.find((r) => r.scene === scene && r.method === method)!;
  const time = (r: LightingMeasurement): number => (cpu ? r.frameCpuMs : r.frameMs);
  return {
    scene, baseline, method,
    equalSamples: b.relativeVariance / m.relativeVariance,
    equalTime: (b.relativeVariance * time(b)) / (m.relativeVariance * time(m)),
  };
}

export async function runLightingBenchmark(): Promise<LightingBenchmark> {
  const acquired = await acquireGpuDevice();
  const device = acquired.device;
  const rows: LightingMeasurement[] = [];
  try {
    const sphereScene: Partial<WavefrontPathTracingOptions> = {
      camera: { position: [0, 1.6, 4], target: [0, 0.6, 0], fovYDegrees: 45 },
      meshes: [floor(4)],
      sceneObjects: [{ type: 'sphere', center: [0, 0.8, 0], radius: 0.8, color: [0.8, 0.8, 0.8], metallic: 0, roughness: 1, ior: 1 }],
      environmentMap: sunnyMap(5000),
    };
    rows.push(await measure(device, 'HDRI with a small sun', 'uniform directions', { ...sphereScene, environmentSampling: 'uniform' }));
    rows.push(await measure(device, 'HDRI with a small sun', 'importance sampling', sphereScene));

    // Looking down at the floor: the emitters stay out of view, so the noise is that of light sampling.
    const manyCamera = { position: [0, 1.2, 2.5], target: [0, 0, -0.5], fovYDegrees: 45 };
    const power = 0.6;
    rows.push(await measure(device, 'emitters', '8 triangles', { camera: manyCamera, meshes: [floor(5), emitters(8, 3, power)] }));
    rows.push(await measure(device, 'emitters', '10,000 triangles, light tree', { camera: manyCamera, meshes: [floor(5), emitters(10_000, 3, power)] }));
    rows.push(await measure(device, 'emitters', '10,000 triangles, power table', { camera: manyCamera, meshes: [floor(5), emitters(10_000, 3, power)], lightSampler: 'power' }));

    const roomScene: Partial<WavefrontPathTracingOptions> = {
      camera: { position: [-1.8, 1.6, 1.7], target: [0.5, 0.5, -0.5], fovYDegrees: 70 },
      meshes: [windowRoomMesh()],
      environmentMap: sunnyMap(200),
    };
    rows.push(await measure(device, 'room through a window', 'no portal', roomScene));
    rows.push(await measure(device, 'room through a window', 'portal (guide)', { ...roomScene, environmentPortals: [windowPortal] }));
  } finally {
    if (acquired.ownsDevice) device.destroy();
  }
  const cpu = isCpuAdapter(acquired.adapterDescription);
  return {
    adapter: acquired.adapterDescription,
    time: cpu ? 'worker CPU' : 'wall clock',
    size: SIZE,
    measurements: rows,
    comparisons: [
      compare(rows, 'HDRI with a small sun', 'uniform directions', 'importance sampling', cpu),
      compare(rows, 'emitters', '8 triangles', '10,000 triangles, light tree', cpu),
      compare(rows, 'emitters', '10,000 triangles, power table', '10,000 triangles, light tree', cpu),
      compare(rows, 'room through a window', 'no portal', 'portal (guide)', cpu),
    ],
  };
}

export function printLightingBenchmark(b: LightingBenchmark): void {
  console.log(`\nLighting (${b.size}x${b.size}, ${b.measurements[0]?.spp ?? '?'} spp, two seeds per row; equal time by ${b.time}; adapter ${b.adapter})`);
  console.table(
    b.measurements.map((m) => ({
      scene: m.scene, method: m.method, 'relative variance': Number(m.relativeVariance.toPrecision(3)), 'frame ms': Math.round(m.frameMs), 'frame CPU ms': Math.round(m.frameCpuMs), 'create ms': Math.round(m.createMs),
    })),
  );
  console.table(
    b.comparisons.map((c) => ({
      scene: c.scene, baseline: c.baseline, method: c.method, 'variance ratio (equal spp)': Number(c.equalSamples.toFixed(2)), 'gain at equal time': Number(c.equalTime.toFixed(2)),
    })),
  );
}

if (import.meta.main) {
  printLightingBenchmark(await runLightingBenchmark());
}
