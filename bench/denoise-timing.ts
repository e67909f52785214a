/**
 * OIDN denoise time at a production resolution (default 1920x1080), the case for real GPUs (goal:
 * 1080p in <= 25 ms on an H100/H200): the network (rt_hdr_alb_nrm) on a synthetic noisy HDR image
 * with albedo and normal in GPU buffers, in every precision the device runs (f16 needs
 * shader-f16), tiles as the default 1 GiB budget and the device's binding limits allow. One
 * warm-up denoise, then BENCH_DENOISE_RUNS (default 10) denoises in one submission: the GPU time
 * per denoise from timestamp queries where the device has them, and the wall time per denoise.
 *
 *   npm run generate && node bench/denoise-timing.ts                # 1920x1080
 *   BENCH_DENOISE_SIZE=512x512 BENCH_DENOISE_RUNS=3 node bench/denoise-timing.ts
 *
 * Prints a table; writes bench/results/denoise-timing.json.
 */
import { mkdir, writeFile } from 'node:fs/promises';
import { fileURLToPath } from 'node:url';
import { acquireGpuDevice } from '../src/gpu/acquire-device.ts';
import { BufferUsage, MapMode } from '../src/gpu/webgpu-constants.ts';
import { OidnNetwork } from '../src/film/denoise/oidn/oidn-network.ts';
import type { OidnPrecision } from '../src/film/denoise/oidn/packing.ts';
import { loadOidnModel } from '../src/film/denoise/oidn/weights.ts';

export interface DenoiseTimingRow {
  precision: OidnPrecision;
  width: number;
  height: number;
  tiles: number;
  tileSize: string;
  memoryMiB: number;
  gpuMs: number | null;
  wallMs: number;
  /** Multiply-adds of the network per second (10^9), from the GPU time where measured (else the wall time). */
  gigaMacsPerSecond: number;
}

function buffer(device: GPUDevice, width: number, height: number, f: (x: number, y: number, c: number) => number): GPUBuffer {
  const data = new Float32Array(width * height * 4);
  for (let y = 0; y < height; y++) for (let x = 0; x < width; x++) for (let c = 0; c < 4; c++) data[4 * (y * width + x) + c] = f(x, y, c);
  const b = device.createBuffer({ size: data.byteLength, usage: BufferUsage.STORAGE | BufferUsage.COPY_DST });
  device.queue.writeBuffer(b, 0, data);
  return b;
}

export async function runDenoiseTiming(width: number, height: number, runs: number): Promise<{ adapter: string; rows: DenoiseTimingRow[] }> {
  const acquired = await acquireGpuDevice({ optionalFeatures: ['timestamp-query', 'shader-f16'] });
  const device = acquired.device;
  const model = await loadOidnModel('rt_hdr_alb_nrm');
  // Multiply-adds per pixel of the full-resolution tile: each convolution at its level.
  const macsPerPixel = model.convs.reduce((a, c) => a + (9 * c.sourceChannels.reduce((x, y) => x + y, 0) * c.outChannels) / 4 ** c.level, 0);
  let seed = 1;
  const rand = () => ((seed = (seed * 16807) % 2147483647) / 2147483647);
  const color = buffer(device, width, height, (x, _y, c) => (c === 3 ? 1 : (x % 64 < 32 ? 0.3 : 2) * (rand() < 0.05 ? 30 * rand() : 2 * rand())));
  const albedo = buffer(device, width, height, (x, y, c) => (c === 3 ? 1 : 0.2 + 0.6 * (((x >> 5) + (y >> 5)) % 2)));
  const normal = buffer(device, width, height, (x, y, c) => [Math.sin(x / 100), 1, Math.cos(y / 100), 0][c]!);
  const output = device.createBuffer({ size: width * height * 16, usage: BufferUsage.STORAGE });
  const precisions: OidnPrecision[] = device.features.has('shader-f16') ? ['f16', 'f32'] : ['f32'];
  const rows: DenoiseTimingRow[] = [];
  for (const precision of precisions) {
    const network = await OidnNetwork.create(device, model, { precision });
    const denoiser = network.createImageDenoiser(width, height, { color, albedo: { buffer: albedo }, normal: { buffer: normal } }, output);
    const timing = acquired.timestampQueries ? { set: device.createQuerySet({ type: 'timestamp', count: 2 * runs }), resolve: device.createBuffer({ size: 16 * runs, usage: BufferUsage.QUERY_RESOLVE | BufferUsage.COPY_SRC }), read: device.createBuffer({ size: 16 * runs, usage: BufferUsage.MAP_READ | BufferUsage.COPY_DST }) } : null;
    // Warm-up: pipelines, first-use allocations.
    let encoder = device.createCommandEncoder();
    denoiser.encode(encoder);
    device.queue.submit([encoder.finish()]);
    await device.queue.onSubmittedWorkDone();
    encoder = device.createCommandEncoder();
    for (let i = 0; i < runs; i++) denoiser.encode(encoder, timing ? { querySet: timing.set, beginningOfPassWriteIndex: 2 * i, endOfPassWriteIndex: 2 * i + 1 } : undefined);
    if (timing) {
      encoder.resolveQuerySet(timing.set, 0, 2 * runs, timing.resolve, 0);
      encoder.copyBufferToBuffer(timing.resolve, 0, timing.read, 0, 16 * runs);
    }
    const t0 = performance.now();
    device.queue.submit([encoder.finish()]);
    await device.queue.onSubmittedWorkDone();
    const wallMs = (performance.now() - t0) / runs;
    let gpuMs: number | null = null;
    if (timing) {
      await timing.read.mapAsync(MapMode.READ);
      const t = new BigUint64Array(timing.read.getMappedRange().slice(0));
      timing.read.unmap();
      const each = Array.from({ length: runs }, (_, i) => Number(t[2 * i + 1]! - t[2 * i]!) / 1e6).sort((a, b) => a - b);
      gpuMs = each[Math.floor(runs / 2)]!;
    }
    rows.push({
      precision,
      width,
      height,
      tiles: denoiser.tiles.tiles.length,
      tileSize: `${denoiser.tiles.tileWidth}x${denoiser.tiles.tileHeight}`,
      memoryMiB: denoiser.memoryBytes / 2 ** 20,
      gpuMs,
      wallMs,
      gigaMacsPerSecond: (macsPerPixel * denoiser.tiles.tileWidth * denoiser.tiles.tileHeight * denoiser.tiles.tiles.length) / ((gpuMs ?? wallMs) * 1e-3) / 1e9,
    });
    denoiser.destroy();
    network.destroy();
  }
  return { adapter: acquired.adapterDescription, rows };
}

if (import.meta.url === `file://${process.argv[1]}`) {
  const [w, h] = (process.env.BENCH_DENOISE_SIZE ?? '1920x1080').split('x').map(Number) as [number, number];
  const runs = Number(process.env.BENCH_DENOISE_RUNS ?? 10);
  const result = await runDenoiseTiming(w, h, runs);
  console.log(`OIDN rt_hdr_alb_nrm ${w}x${h}, median of ${runs} on ${result.adapter}`);
  console.table(result.rows.map((r) => ({ precision: r.precision, tiles: `${r.tiles} x ${r.tileSize}`, 'memory (MiB)': r.memoryMiB.toFixed(0), 'GPU ms': r.gpuMs?.toFixed(2) ?? 'n/a', 'wall ms': r.wallMs.toFixed(2), 'GMAC/s': r.gigaMacsPerSecond.toFixed(1) })));
  const out = fileURLToPath(new URL('./results/', import.meta.url));
  await mkdir(out, { recursive: true });
  await writeFile(`${out}denoise-timing.json`, `${JSON.stringify({ date: new Date().toISOString(), ...result }, null, 2)}\n`);
  process.exit(0);
}
