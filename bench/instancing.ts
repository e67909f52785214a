/**
 * Instancing benchmark (issue 25): what two-level acceleration costs and buys.
 *
 * 1. Forest: a generated .glb (bench/instancing-assets.ts) of a terrain (one mesh, placed once) and
 *    four tree meshes of about 20k, 40k, 60k and 100k triangles with BENCH_INSTANCING_COUNT (10,000)
 *    EXT_mesh_gpu_instancing placements in all (random tree, yaw and scale), loaded with
 *    `loadGltfScene(path, { defaultLighting: 'neutral' })` as the CLI loads a .glb. Timed: the load;
 *    the scene preparation the renderer runs (`prepareGeometry`), split into the bottom-level builds
 *    (sum over the shared meshes, CPU binned SAH) and the top-level build on the CPU; the top level
 *    built on the GPU (`GpuBvhBuilder` over the same top-level records, what
 *    `accelerationBuildMode: 'gpu'` runs); each for 'auto' (the terrain, placed once, flattened into
 *    the top level) and 'always' (the top level holds the placements alone); and, for comparison
 *    only, the GPU LBVH of each tree mesh (the renderer builds bottom levels on the CPU). Median
 *    (min-max) of BENCH_INSTANCING_RUNS (3).
 *    Then two renderers on one device, the top level built on the CPU and on the GPU: memory,
 *    bytes per placement, and samples/s, rays/s at BENCH_INSTANCING_SIZE^2 (256), maxDepth 8,
 *    BENCH_INSTANCING_SPP (2) spp per timed frame, frames alternated for BENCH_INSTANCING_ROUNDS (5)
 *    rounds after an untimed warm-up each.
 * 2. TLAS update per moved frame: `updateGeometry` turning every tree placement by 0.02 rad more
 *    about its trunk each frame, BENCH_INSTANCING_UPDATES (10) frames with `bvh: 'refit'` then as
 *    many with `'rebuild'`, on both renderers: median totalMs and accelerationMs; and the CPU side
 *    alone: the same updates packed by the renderer's own functions outside any renderer
 *    (`packGeometryUpdate`: validation, transforms, placement boxes, instance records; plus the
 *    primitive records of the top level and, for a CPU rebuild, its binned-SAH build).
 * 3. Flattened against instanced where both fit: the same generator with BENCH_INSTANCING_SMALL (32)
 *    placements, the most whose flattened copy fits a 128 MiB storage binding (lavapipe's limit),
 *    rendered with instancing 'off', 'always' and 'auto' on one device, frames alternated.
 * 4. One mesh placed once: the displaced 1,310,720-triangle icosphere of bench/pathtracer.ts alone
 *    under a uniform sky, 'off' (what 'auto' does with a mesh placed once) against 'always' (one
 *    top-level record over one bottom level): what entering a bottom level costs.
 *
 * Samples/s = pixels x spp / wall seconds of renderFrame; on a CPU adapter also samples per
 * CPU-second of the driver's threads (cpu-clock.ts). bench/run.ts runs this in a child process
 * (instancing-child.ts); `node bench/instancing-child.ts --print` runs it alone.
 */
import { mkdtemp, rm, stat, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { buildBvhAsync, terminateBvhWorkers, warmBvhWorkers } from '../src/accel/bvh-builder.ts';
import { GpuBvhBuilder } from '../src/accel/gpu-build/gpu-bvh-builder.ts';
import { bvhParentLinks, packPrimitives, packWavefrontBvhNodes, packWavefrontTriangles } from '../src/accel/triangle-packing.ts';
import { acquireGpuDevice } from '../src/gpu/acquire-device.ts';
import { BufferUsage } from '../src/gpu/webgpu-constants.ts';
import { bvhNodeLayout, primitiveLayout } from '../src/gpu-layout/records.ts';
import { loadGltfScene } from '../src/io/index.ts';
import { createWavefrontPathTracingComputeRenderer } from '../src/pathtracer/index.ts';
import { packGeometryUpdate, type WavefrontGeometryUpdate } from '../src/pathtracer/scene/geometry-update.ts';
import { planInstancing, type InstancingMode } from '../src/pathtracer/scene/instancing.ts';
import { applyTopLevelPatch } from '../src/pathtracer/scene/top-level-patch.ts';
import { prepareGeometry, prepareMaterials, type PreparedMaterials, type PreparedScene } from '../src/pathtracer/scene/prepare-scene.ts';
import type { WavefrontInstancingStats, WavefrontPathTracingOptions, WavefrontPathTracingRenderer } from '../src/pathtracer/types.ts';
import { normalizeWavefrontScene, type NormalizedScene } from '../src/scene/normalize-scene.ts';
import type { WavefrontCameraInput, WavefrontSceneDescription } from '../src/scene/types.ts';
import { isCpuAdapter } from './cpu-clock.ts';
import { roundFigures, timedRounds, type RoundRow } from './timed-rounds.ts';
import { forestGlb, TREES, type ForestAsset } from './instancing-assets.ts';
import { icosphere } from './pathtracer.ts';
import { envInteger, spread, type Spread } from './gltf.ts';

export type { Spread } from './gltf.ts';

type BuildMode = 'cpu-upload' | 'gpu';

export interface InstancingRenderRow extends RoundRow {
  scene: string;
  instancing: InstancingMode;
  accelerationBuildMode: BuildMode;
  /** createWavefrontPathTracingComputeRenderer wall ms (preparation, BVH, upload, pipelines). */
  createMs: number;
  stats: WavefrontInstancingStats;
  triangles: number;
  sceneBytes: number;
  bvhNodes: number;
  bvhDepth: number;
}

export interface PrepareTimes {
  instancing: InstancingMode;
  /** prepareGeometry wall ms (vertex streams, flattening, every BVH, packing). */
  prepareMs: number;
  /** Bottom levels: records and CPU builds of every shared mesh, ms (0 when none). */
  bottomLevelMs: number;
  /** The top-level (or only) tree on the CPU, ms. */
  topLevelMs: number;
  topLevelRecords: number;
  sharedMeshes: number;
  flattenedTriangles: number;
}

export interface ForestBuildRow {
  instancing: InstancingMode;
  runs: number;
  prepareMs: Spread;
  bottomLevelMs: Spread;
  topLevelCpuMs: Spread;
  /** GpuBvhBuilder over the same top-level records: wall (submission to figures read back) and timestamp time. */
  topLevelGpuMs: Spread;
  topLevelGpuTimeMs: Spread | null;
  topLevelRecords: number;
  /** SAH cost of the GPU top level over the CPU one's. */
  topLevelSahGpuOverCpu: number;
}

export interface UpdateRow {
  accelerationBuildMode: BuildMode;
  bvh: 'refit' | 'rebuild';
  frames: number;
  placementsMoved: number;
  /** updateGeometry's own figures: the whole update, and the BVH part of it (wall ms). */
  totalMs: Spread;
  accelerationMs: Spread;
  /** The CPU work of the same updates outside the renderer (see the file comment), ms. */
  cpuMs: Spread;
}

export interface InstancingBenchResult {
  name: 'instancing';
  node: string;
  adapter: string;
  /** The device's maxStorageBufferBindingSize: what decides whether a flattened scene fits. */
  maxStorageBufferBindingSize: number;
  maxDepth: number;
  rounds: number;
  forest: {
    placements: number;
    side: number;
    trees: { name: string; triangles: number; placements: number }[];
    terrainTriangles: number;
    /** Triangles over every placement: what instancing 'off' would store. */
    placedTriangles: number;
    fileBytes: number;
    /** loadGltfScene of the .glb: the first of the process, then again. */
    firstLoadMs: number;
    loadMs: number;
    /** Builds of 'auto' (the renderer's default: the terrain flattened into the top level) and 'always' (every placement). */
    build: ForestBuildRow[];
    /** GPU LBVH of each tree mesh, one timed build each after a warm-up: not what the renderer runs (bottom levels build on the CPU). */
    bottomLevelGpuLbvhMs: number;
    bottomLevelGpuLbvhTimeMs: number | null;
    renders: InstancingRenderRow[];
    updates: UpdateRow[];
  };
  flattenedVsInstanced: {
    placements: number;
    placedTriangles: number;
    prepare: PrepareTimes[];
    renders: InstancingRenderRow[];
    /** samples/s of 'always' and 'auto' over 'off' (medians), and per round. */
    overOff: { instancing: InstancingMode; samplesPerSecond: number; perRound: number[]; samplesPerWorkerCpuSecond: number | null; sceneBytes: number }[];
  };
  singleMesh: {
    triangles: number;
    autoFlattens: boolean;
    prepare: PrepareTimes[];
    renders: InstancingRenderRow[];
    alwaysOverOff: { samplesPerSecond: number; perRound: number[]; samplesPerWorkerCpuSecond: number | null };
  };
  /**
   * What a placement costs, measured: scene bytes of the forest ('auto', CPU top level) minus those
   * of the small forest ('auto': the same meshes and terrain, fewer placements), per placement.
   */
  measuredBytesPerPlacement: number | null;
  totalSeconds: number;
}

const MAX_DEPTH = 8;

/** Column-major 4x4 product a * b. */
function multiply(a: ArrayLike<number>, b: ArrayLike<number>): number[] {
  const out = new Array<number>(16).fill(0);
  for (let c = 0; c < 4; c++) for (let r = 0; r < 4; r++) for (let k = 0; k < 4; k++) out[4 * c + r]! += a[4 * k + r]! * b[4 * c + k]!;
  return out;
}

function rotationY(angle: number): number[] {
  const c = Math.cos(angle), s = Math.sin(angle);
  return [c, 0, -s, 0, 0, 1, 0, 0, s, 0, c, 0, 0, 0, 0, 1];
}

const IDENTITY = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];

/** Frame k's update: every placement of a tree mesh turned by 0.02 k rad about its own y axis; the rest kept. */
function turnedTrees(scene: WavefrontSceneDescription, trees: ReadonlySet<number>, k: number, bvh: 'refit' | 'rebuild'): WavefrontGeometryUpdate {
  const turn = rotationY(0.02 * k);
  return { bvh, instances: (scene.instances ?? []).map((inst) => (trees.has(inst.mesh) ? { transform: multiply(inst.transform ?? IDENTITY, turn) } : null)) };
}

interface Prepared {
  normalized: NormalizedScene;
  materials: PreparedMaterials;
}

function normalize(scene: WavefrontSceneDescription, device: GPUDevice): Prepared {
  const normalized = normalizeWavefrontScene(scene);
  const limits = { maxTextureDimension2D: device.limits.maxTextureDimension2D, maxTextureArrayLayers: device.limits.maxTextureArrayLayers };
  return { normalized, materials: prepareMaterials(normalized, limits) };
}

async function timePrepare(p: Prepared, instancing: InstancingMode, accelerationBuildMode: BuildMode = 'cpu-upload'): Promise<{ times: PrepareTimes; prepared: PreparedScene }> {
  const t0 = performance.now();
  const prepared = await prepareGeometry(p.normalized, p.materials, { instancing, accelerationBuildMode });
  const prepareMs = performance.now() - t0;
  return {
    prepared,
    times: {
      instancing, prepareMs, bottomLevelMs: prepared.bottomLevels?.buildTimeMs ?? 0, topLevelMs: prepared.bvh.buildTimeMs,
      topLevelRecords: prepared.primitiveCount, sharedMeshes: prepared.instancing.bottomLevels.length, flattenedTriangles: prepared.instancing.flattenedTriangles,
    },
  };
}

/** A GPU LBVH over packed primitive records (scene order), its output buffers sized for them. */
async function gpuBuild(device: GPUDevice, records: ArrayBuffer, count: number): Promise<{ run: () => Promise<{ wallMs: number; gpuMs: number | null; sahCost: number }>; destroy: () => void }> {
  const usage = BufferUsage.STORAGE | BufferUsage.COPY_DST;
  const buffers = {
    source: device.createBuffer({ size: records.byteLength, usage }),
    primitives: device.createBuffer({ size: count * primitiveLayout.size, usage }),
    nodes: device.createBuffer({ size: (2 * count - 1) * bvhNodeLayout.size, usage }),
    parents: device.createBuffer({ size: (2 * count - 1) * 4, usage }),
  };
  device.queue.writeBuffer(buffers.source, 0, records);
  const builder = await GpuBvhBuilder.create(device, { ...buffers, primitiveCount: count });
  await builder.build(); // untimed: scratch allocation
  return {
    run: async () => {
      const r = await builder.build();
      return { wallMs: r.buildTimeMs, gpuMs: r.gpuTimeMs, sahCost: r.sahCost };
    },
    destroy: () => {
      builder.destroy();
      for (const b of Object.values(buffers)) b.destroy();
    },
  };
}

/** Object-space triangle soup of a normalized mesh (9 floats per triangle). */
function soup(scene: NormalizedScene, mesh: number): Float32Array {
  const m = scene.meshes[mesh]!;
  const out = new Float32Array(9 * m.triangleCount);
  for (let i = 0; i < 3 * m.triangleCount; i++) out.set(m.positions.subarray(3 * m.indices[i]!, 3 * m.indices[i]! + 3), 3 * i);
  return out;
}

interface Variant {
  scene: string;
  instancing: InstancingMode;
  accelerationBuildMode: BuildMode;
}

interface LiveRenderers {
  renderers: WavefrontPathTracingRenderer[];
  createMs: number[];
  destroy: () => void;
}

async function createRenderers(device: GPUDevice, description: WavefrontSceneDescription & Partial<WavefrontPathTracingOptions>, variants: Variant[], size: number, log: (line: string) => void): Promise<LiveRenderers> {
  const renderers: WavefrontPathTracingRenderer[] = [];
  const createMs: number[] = [];
  const destroy = (): void => {
    for (const r of renderers) r.destroy();
  };
  try {
    for (const v of variants) {
      const t0 = performance.now();
      const renderer = await createWavefrontPathTracingComputeRenderer({
        ...description, device, width: size, height: size, maxDepth: MAX_DEPTH, samplesPerPixel: 1, instancing: v.instancing, accelerationBuildMode: v.accelerationBuildMode,
      } as WavefrontPathTracingOptions);
      createMs.push(performance.now() - t0);
      renderers.push(renderer);
      await renderer.renderFrame({ samplesPerPixel: 1 }); // warm-up: pipelines compile on first use
      log(`    ${v.scene}, instancing '${v.instancing}', ${v.accelerationBuildMode}: created in ${createMs.at(-1)!.toFixed(0)} ms`);
    }
  } catch (error) {
    destroy();
    throw error;
  }
  return { renderers, createMs, destroy };
}

/** Timed frames of each renderer in turn, `rounds` times. */
async function renderRounds(live: LiveRenderers, variants: Variant[], size: number, spp: number, rounds: number, log: (line: string) => void): Promise<{ rows: InstancingRenderRow[]; samples: number[][] }> {
  const figures = await timedRounds(live.renderers, size * size, spp, rounds, (r, samples) => {
    log(`    round ${r + 1}/${rounds}: ${variants.map((v, k) => `'${v.instancing}'${v.accelerationBuildMode === 'gpu' ? ' (GPU TLAS)' : ''} ${(samples[k]![r]! / 1e6).toFixed(3)}`).join(', ')} M samples/s`);
  });
  const cpu = isCpuAdapter(live.renderers[0]!.getSnapshot().adapter);
  const rows = variants.map((v, k): InstancingRenderRow => {
    const s = live.renderers[k]!.getSnapshot();
    return {
      scene: v.scene, instancing: v.instancing, accelerationBuildMode: v.accelerationBuildMode, createMs: live.createMs[k]!, stats: s.instancing,
      triangles: s.triangleCount, sceneBytes: s.memory.sceneBytes, bvhNodes: s.bvhNodeCount, bvhDepth: s.bvhDepth,
      ...roundFigures(figures, k, cpu, size, spp),
    };
  });
  return { rows, samples: figures.samples };
}

/**
 * The CPU side of one update as the renderer runs it (renderer-updates.ts, scene-acceleration.ts),
 * outside any renderer: packGeometryUpdate, then either the patch of the moved placements' records
 * (a refit that moves instances only: applyTopLevelPatch, on the bench's own prepared scene) or the
 * top level's primitive records and, for a CPU rebuild, its binned-SAH build, node records and
 * parent links. Nothing is uploaded or waited for.
 */
async function cpuSideOfUpdate(p: Prepared, prepared: PreparedScene, update: WavefrontGeometryUpdate, mode: BuildMode): Promise<number> {
  const t0 = performance.now();
  const packed = packGeometryUpdate(p.normalized, prepared, update);
  const { flat, patch } = packed.topLevel;
  if (patch) {
    applyTopLevelPatch(prepared, patch);
  } else if (mode === 'gpu') {
    packPrimitives(flat, Uint32Array.from({ length: flat.count }, (_, i) => i));
  } else if (packed.bvh === 'refit') {
    packPrimitives(flat, prepared.acceleration.order!);
  } else {
    const bvh = await buildBvhAsync(flat.boundsTriangles);
    const nodes = packWavefrontBvhNodes(bvh);
    packPrimitives(flat, bvh.triangleOrder);
    bvhParentLinks(nodes, bvh.nodeCount);
  }
  return performance.now() - t0;
}

async function measureUpdates(
  live: LiveRenderers, variants: Variant[], p: Prepared, prepared: Record<BuildMode, PreparedScene>, scene: WavefrontSceneDescription, trees: ReadonlySet<number>, frames: number, log: (line: string) => void,
): Promise<UpdateRow[]> {
  const rows: UpdateRow[] = [];
  const placementsMoved = (scene.instances ?? []).filter((inst) => trees.has(inst.mesh)).length;
  for (let k = 0; k < variants.length; k++) {
    const mode = variants[k]!.accelerationBuildMode;
    let frame = 0;
    for (const bvh of ['refit', 'rebuild'] as const) {
      const total: number[] = [];
      const acceleration: number[] = [];
      const cpu: number[] = [];
      for (let f = 0; f < frames; f++) {
        const update = turnedTrees(scene, trees, ++frame, bvh);
        const stats = await live.renderers[k]!.updateGeometry(update);
        total.push(stats.totalMs);
        acceleration.push(stats.accelerationMs);
        cpu.push(await cpuSideOfUpdate(p, prepared[mode], update, mode));
      }
      const row: UpdateRow = { accelerationBuildMode: mode, bvh, frames, placementsMoved, totalMs: spread(total), accelerationMs: spread(acceleration), cpuMs: spread(cpu) };
      rows.push(row);
      log(`    ${mode} ${bvh}: total ${row.totalMs.median.toFixed(1)} ms, acceleration ${row.accelerationMs.median.toFixed(1)} ms, CPU side ${row.cpuMs.median.toFixed(1)} ms (medians of ${frames})`);
    }
    // One frame after the moves: the renderer still traces (and the figures are of a working renderer).
    await live.renderers[k]!.renderFrame({ samplesPerPixel: 1 });
  }
  return rows;
}

async function loadForest(dir: string, asset: ForestAsset, name: string): Promise<{ path: string; fileBytes: number }> {
  const path = join(dir, name);
  await writeFile(path, asset.glb);
  return { path, fileBytes: (await stat(path)).size };
}

/** The loaded scene as renderer options: enumerable keys only (the loader's metadata is not), and the asset's camera. */
async function loadAsRendered(path: string, camera: WavefrontCameraInput): Promise<{ description: WavefrontSceneDescription; ms: number }> {
  const t0 = performance.now();
  const scene = await loadGltfScene(path, { defaultLighting: 'neutral' });
  const ms = performance.now() - t0;
  return { description: { ...scene, camera }, ms };
}

function treeMeshes(scene: WavefrontSceneDescription): Set<number> {
  // The terrain is the mesh placed once; the trees are every mesh placed more than once.
  const counts = new Map<number, number>();
  for (const inst of scene.instances ?? []) counts.set(inst.mesh, (counts.get(inst.mesh) ?? 0) + 1);
  return new Set([...counts].filter(([, n]) => n > 1).map(([mesh]) => mesh));
}

async function measureForest(device: GPUDevice, dir: string, size: number, spp: number, rounds: number, log: (line: string) => void): Promise<InstancingBenchResult['forest']> {
  const count = envInteger('BENCH_INSTANCING_COUNT', 10_000);
  const runs = envInteger('BENCH_INSTANCING_RUNS', 3);
  const frames = envInteger('BENCH_INSTANCING_UPDATES', 10);
  const asset = await forestGlb(count);
  const { path, fileBytes } = await loadForest(dir, asset, 'forest.glb');
  log(`  forest.glb: ${count.toLocaleString('en-US')} placements of ${TREES.length} trees (${asset.treeTriangles.map((t) => t.toLocaleString('en-US')).join(', ')} triangles) on a ${asset.terrainTriangles.toLocaleString('en-US')}-triangle terrain, ${(fileBytes / 2 ** 20).toFixed(1)} MiB, ${asset.placedTriangles.toLocaleString('en-US')} placed triangles`);
  const first = await loadAsRendered(path, asset.camera);
  const again = await loadAsRendered(path, asset.camera);
  const scene = again.description;
  log(`  load: ${first.ms.toFixed(0)} ms (first of the process), ${again.ms.toFixed(0)} ms again`);

  const p = normalize(scene, device);
  const build: ForestBuildRow[] = [];
  let cpuPrepared: PreparedScene | null = null;
  let gpuPrepared: PreparedScene | null = null;
  for (const instancing of ['auto', 'always'] as const) {
    const prepareMs: number[] = [];
    const bottomMs: number[] = [];
    const topCpuMs: number[] = [];
    let cpu: PreparedScene | null = null;
    for (let r = 0; r < runs; r++) {
      const { times, prepared } = await timePrepare(p, instancing);
      cpu = prepared;
      prepareMs.push(times.prepareMs);
      bottomMs.push(times.bottomLevelMs);
      topCpuMs.push(times.topLevelMs);
      log(`  '${instancing}' prepare run ${r + 1}/${runs}: ${times.prepareMs.toFixed(0)} ms, bottom levels ${times.bottomLevelMs.toFixed(0)} ms (${times.sharedMeshes} meshes), top level ${times.topLevelMs.toFixed(1)} ms (${times.topLevelRecords.toLocaleString('en-US')} records)`);
    }
    const { prepared: gpu } = await timePrepare(p, instancing, 'gpu');
    const top = await gpuBuild(device, gpu.primitives, gpu.primitiveCount);
    const topGpu: { wallMs: number; gpuMs: number | null; sahCost: number }[] = [];
    try {
      for (let r = 0; r < runs; r++) topGpu.push(await top.run());
    } finally {
      top.destroy();
    }
    const gpuTimes = topGpu.map((t) => t.gpuMs).filter((t): t is number => t !== null);
    const row: ForestBuildRow = {
      instancing, runs, prepareMs: spread(prepareMs), bottomLevelMs: spread(bottomMs), topLevelCpuMs: spread(topCpuMs), topLevelGpuMs: spread(topGpu.map((t) => t.wallMs)),
      topLevelGpuTimeMs: gpuTimes.length === topGpu.length ? spread(gpuTimes) : null, topLevelRecords: cpu!.primitiveCount, topLevelSahGpuOverCpu: topGpu.at(-1)!.sahCost / cpu!.bvh.sahCost,
    };
    build.push(row);
    log(`  '${instancing}' top level on the GPU: ${row.topLevelGpuMs.median.toFixed(1)} ms wall (median of ${runs})`);
    if (instancing === 'auto') {
      cpuPrepared = cpu;
      gpuPrepared = gpu;
    }
  }
  let lbvhMs = 0;
  let lbvhGpuMs: number | null = 0;
  for (const b of gpuPrepared!.instancing.bottomLevels) {
    const triangles = soup(p.normalized, b.mesh);
    const n = triangles.length / 9;
    const builder = await gpuBuild(device, packWavefrontTriangles(triangles, Uint32Array.from({ length: n }, (_, i) => i)), n);
    try {
      const t = await builder.run();
      lbvhMs += t.wallMs;
      lbvhGpuMs = t.gpuMs === null || lbvhGpuMs === null ? null : lbvhGpuMs + t.gpuMs;
    } finally {
      builder.destroy();
    }
  }
  log(`  GPU LBVH of the ${gpuPrepared!.instancing.bottomLevels.length} tree meshes (not what the renderer runs): ${lbvhMs.toFixed(0)} ms`);

  const variants: Variant[] = [
    { scene: 'forest', instancing: 'auto', accelerationBuildMode: 'cpu-upload' },
    { scene: 'forest', instancing: 'auto', accelerationBuildMode: 'gpu' },
  ];
  const live = await createRenderers(device, scene, variants, size, log);
  try {
    const { rows } = await renderRounds(live, variants, size, spp, rounds, log);
    log('  updates: every tree placement turned each frame');
    const updates = await measureUpdates(live, variants, p, { 'cpu-upload': cpuPrepared!, gpu: gpuPrepared! }, scene, treeMeshes(scene), frames, log);
    return {
      placements: count, side: asset.side, trees: TREES.map((t, i) => ({ name: t.name, triangles: asset.treeTriangles[i]!, placements: asset.perTree[i]! })),
      terrainTriangles: asset.terrainTriangles, placedTriangles: asset.placedTriangles, fileBytes, firstLoadMs: first.ms, loadMs: again.ms,
      build, bottomLevelGpuLbvhMs: lbvhMs, bottomLevelGpuLbvhTimeMs: lbvhGpuMs,
      renders: rows,
      updates,
    };
  } finally {
    live.destroy();
  }
}

/** Other modes' samples/s over the first variant's, of the medians and per round. */
function overFirst(rows: InstancingRenderRow[], samples: number[][], k: number): { samplesPerSecond: number; perRound: number[]; samplesPerWorkerCpuSecond: number | null } {
  const base = rows[0]!;
  const row = rows[k]!;
  return {
    samplesPerSecond: row.samplesPerSecond.median / base.samplesPerSecond.median,
    perRound: samples[k]!.map((v, r) => v / samples[0]![r]!),
    samplesPerWorkerCpuSecond: row.samplesPerWorkerCpuSecond && base.samplesPerWorkerCpuSecond ? row.samplesPerWorkerCpuSecond.median / base.samplesPerWorkerCpuSecond.median : null,
  };
}

async function measureSmallForest(device: GPUDevice, dir: string, size: number, spp: number, rounds: number, log: (line: string) => void): Promise<InstancingBenchResult['flattenedVsInstanced']> {
  const count = envInteger('BENCH_INSTANCING_SMALL', 32);
  const asset = await forestGlb(count);
  const { path } = await loadForest(dir, asset, 'small-forest.glb');
  log(`  small-forest.glb: ${count} placements, ${asset.placedTriangles.toLocaleString('en-US')} placed triangles`);
  const { description } = await loadAsRendered(path, asset.camera);
  const modes: InstancingMode[] = ['off', 'always', 'auto'];
  const p = normalize(description, device);
  const prepare: PrepareTimes[] = [];
  for (const mode of modes) {
    const { times } = await timePrepare(p, mode);
    prepare.push(times);
    log(`    prepare '${mode}': ${times.prepareMs.toFixed(0)} ms, bottom levels ${times.bottomLevelMs.toFixed(0)} ms, top level ${times.topLevelMs.toFixed(0)} ms (${times.topLevelRecords.toLocaleString('en-US')} records)`);
  }
  const variants = modes.map((instancing): Variant => ({ scene: 'small forest', instancing, accelerationBuildMode: 'cpu-upload' }));
  const live = await createRenderers(device, description, variants, size, log);
  try {
    const { rows, samples } = await renderRounds(live, variants, size, spp, rounds, log);
    const overOff = modes.slice(1).map((instancing, i) => ({ instancing, ...overFirst(rows, samples, i + 1), sceneBytes: rows[i + 1]!.sceneBytes / rows[0]!.sceneBytes }));
    return { placements: count, placedTriangles: asset.placedTriangles, prepare, renders: rows, overOff };
  } finally {
    live.destroy();
  }
}

async function measureSingleMesh(device: GPUDevice, size: number, spp: number, rounds: number, log: (line: string) => void): Promise<InstancingBenchResult['singleMesh']> {
  const subdivisions = envInteger('BENCH_INSTANCING_SINGLE_SUBDIVISIONS', 8);
  const sphere = icosphere(0.35, [0.35, -0.6, 0.2], subdivisions);
  const description: WavefrontSceneDescription & Partial<WavefrontPathTracingOptions> = {
    meshes: [sphere],
    camera: { position: [0.35, -0.45, 1.25], target: [0.35, -0.6, 0.2], up: [0, 1, 0], fovYDegrees: 40 },
    environment: { color: [0.8, 0.85, 1] },
  };
  const triangles = sphere.indices!.length / 3;
  log(`  one mesh placed once: ${triangles.toLocaleString('en-US')}-triangle icosphere`);
  const p = normalize(description, device);
  const autoFlattens = planInstancing(p.normalized, 'auto').bottomLevels.length === 0;
  const modes: InstancingMode[] = ['off', 'always'];
  const prepare: PrepareTimes[] = [];
  for (const mode of modes) {
    const { times } = await timePrepare(p, mode);
    prepare.push(times);
    log(`    prepare '${mode}': ${times.prepareMs.toFixed(0)} ms, bottom levels ${times.bottomLevelMs.toFixed(0)} ms, top level ${times.topLevelMs.toFixed(0)} ms`);
  }
  const variants = modes.map((instancing): Variant => ({ scene: 'one mesh', instancing, accelerationBuildMode: 'cpu-upload' }));
  const live = await createRenderers(device, description, variants, size, log);
  try {
    const { rows, samples } = await renderRounds(live, variants, size, spp, rounds, log);
    return { triangles, autoFlattens, prepare, renders: rows, alwaysOverOff: overFirst(rows, samples, 1) };
  } finally {
    live.destroy();
  }
}

export async function runInstancingBenchmark(options: { log?: (line: string) => void } = {}): Promise<InstancingBenchResult> {
  const log = options.log ?? ((line: string) => console.log(line));
  const began = performance.now();
  const size = envInteger('BENCH_INSTANCING_SIZE', 256);
  const spp = envInteger('BENCH_INSTANCING_SPP', 2);
  const rounds = envInteger('BENCH_INSTANCING_ROUNDS', 5);
  const acquired = await acquireGpuDevice();
  const device = acquired.device;
  const dir = await mkdtemp(join(tmpdir(), 'gpu-renderer-bench-instancing-'));
  // Bottom levels of 50k+ triangles and the 1.3M-triangle flattened trees build on the worker pool.
  await warmBvhWorkers(Math.max(1, Math.min(8, navigator.hardwareConcurrency || 2)));
  try {
    log('  forest');
    const forest = await measureForest(device, dir, size, spp, rounds, log);
    log('  flattened against instanced');
    const flattenedVsInstanced = await measureSmallForest(device, dir, size, spp, rounds, log);
    log('  one mesh placed once');
    const singleMesh = await measureSingleMesh(device, size, spp, rounds, log);
    const big = forest.renders.find((r) => r.instancing === 'auto' && r.accelerationBuildMode === 'cpu-upload');
    const small = flattenedVsInstanced.renders.find((r) => r.instancing === 'auto');
    const sameMeshes = big && small && big.stats.sharedMeshes === small.stats.sharedMeshes && big.stats.placements > small.stats.placements;
    const measuredBytesPerPlacement = sameMeshes ? (big.sceneBytes - small.sceneBytes) / (big.stats.placements - small.stats.placements) : null;
    return {
      name: 'instancing', node: process.version, adapter: acquired.adapterDescription, maxStorageBufferBindingSize: device.limits.maxStorageBufferBindingSize,
      maxDepth: MAX_DEPTH, rounds, forest, flattenedVsInstanced, singleMesh, measuredBytesPerPlacement, totalSeconds: (performance.now() - began) / 1000,
    };
  } finally {
    terminateBvhWorkers();
    await rm(dir, { recursive: true, force: true });
    if (acquired.ownsDevice) device.destroy();
  }
}

/** The result as printed tables (bench/run.ts and instancing-child.ts). */
export function printInstancingResult(result: InstancingBenchResult, print: (value: unknown) => void = console.table, log: (line: string) => void = console.log): void {
  const ms = (s: Spread, digits = 0): string => `${s.median.toFixed(digits)} (${s.min.toFixed(digits)}-${s.max.toFixed(digits)})`;
  const mib = (bytes: number): number => Number((bytes / 2 ** 20).toFixed(1));
  const mega = (s: Spread | null): string => (s === null ? '' : `${(s.median / 1e6).toFixed(3)} (${(s.min / 1e6).toFixed(3)}-${(s.max / 1e6).toFixed(3)})`);
  const f = result.forest;
  log(`forest: ${f.placements.toLocaleString('en-US')} placements (${f.trees.map((t) => `${t.name} ${t.triangles.toLocaleString('en-US')} x ${t.placements}`).join(', ')}), terrain ${f.terrainTriangles.toLocaleString('en-US')} triangles; ${f.placedTriangles.toLocaleString('en-US')} placed triangles; ${mib(f.fileBytes)} MiB .glb; load ${f.loadMs.toFixed(0)} ms (first of the process ${f.firstLoadMs.toFixed(0)} ms)`);
  print(f.build.map((b) => ({
    instancing: b.instancing, 'prepare ms': ms(b.prepareMs), 'BLAS ms (CPU, sum)': ms(b.bottomLevelMs), 'TLAS ms CPU': ms(b.topLevelCpuMs, 1),
    'TLAS ms GPU (wall)': ms(b.topLevelGpuMs, 1), 'TLAS GPU time ms': b.topLevelGpuTimeMs ? ms(b.topLevelGpuTimeMs, 1) : '', 'TLAS records': b.topLevelRecords,
    'TLAS SAH GPU/CPU': Number(b.topLevelSahGpuOverCpu.toFixed(3)), runs: b.runs,
  })));
  log(`GPU LBVH of the tree meshes, for comparison (the renderer builds bottom levels on the CPU): ${f.bottomLevelGpuLbvhMs.toFixed(0)} ms wall${f.bottomLevelGpuLbvhTimeMs === null ? '' : `, ${f.bottomLevelGpuLbvhTimeMs.toFixed(0)} ms GPU time`} (sum)`);
  const renderTable = (rows: InstancingRenderRow[]): void => print(rows.map((r) => ({
    scene: r.scene, instancing: r.instancing, TLAS: r.accelerationBuildMode === 'gpu' ? 'GPU' : 'CPU', 'create ms': Math.round(r.createMs),
    'shared meshes': r.stats.sharedMeshes, placements: r.stats.placements, 'flattened tris': r.stats.flattenedTriangles, 'scene MiB': mib(r.sceneBytes), 'B/placement': r.stats.placements ? r.stats.bytesPerPlacement : '',
    'BVH nodes': r.bvhNodes, size: r.resolution, spp: r.spp, 'M samples/s': mega(r.samplesPerSecond), 'M rays/s': mega(r.raysPerSecond), 'M samples/CPU-s': mega(r.samplesPerWorkerCpuSecond),
    'other load': r.otherLoadCores ? `${r.otherLoadCores.median.toFixed(2)} (max ${r.otherLoadCores.max.toFixed(2)})` : '',
  })));
  renderTable(f.renders);
  if (result.measuredBytesPerPlacement !== null) log(`bytes per placement, measured (scene bytes of the forest minus the small forest's, per placement): ${result.measuredBytesPerPlacement.toFixed(0)}`);
  print(f.updates.map((u) => ({
    TLAS: u.accelerationBuildMode === 'gpu' ? 'GPU' : 'CPU', bvh: u.bvh, 'placements moved': u.placementsMoved, frames: u.frames,
    'total ms': ms(u.totalMs, 1), 'acceleration ms': ms(u.accelerationMs, 1), 'CPU side ms': ms(u.cpuMs, 1),
  })));
  const s = result.flattenedVsInstanced;
  log(`flattened against instanced: ${s.placements} placements, ${s.placedTriangles.toLocaleString('en-US')} placed triangles (the device binds at most ${mib(result.maxStorageBufferBindingSize)} MiB per storage buffer)`);
  print(s.prepare.map((t) => ({ instancing: t.instancing, 'prepare ms': Math.round(t.prepareMs), 'BLAS ms': Math.round(t.bottomLevelMs), 'TLAS ms': Math.round(t.topLevelMs), 'TLAS records': t.topLevelRecords, 'shared meshes': t.sharedMeshes })));
  renderTable(s.renders);
  for (const o of s.overOff) log(`'${o.instancing}' / 'off': samples/s ${o.samplesPerSecond.toFixed(3)} (rounds: ${o.perRound.map((r) => r.toFixed(2)).join(' ')})${o.samplesPerWorkerCpuSecond === null ? '' : `, per CPU-s ${o.samplesPerWorkerCpuSecond.toFixed(3)}`}, scene bytes ${o.sceneBytes.toFixed(3)}`);
  const m = result.singleMesh;
  log(`one mesh placed once: ${m.triangles.toLocaleString('en-US')} triangles ('auto' ${m.autoFlattens ? 'flattens it, as \'off\'' : 'instances it'})`);
  print(m.prepare.map((t) => ({ instancing: t.instancing, 'prepare ms': Math.round(t.prepareMs), 'BLAS ms': Math.round(t.bottomLevelMs), 'TLAS ms': Math.round(t.topLevelMs), 'TLAS records': t.topLevelRecords })));
  renderTable(m.renders);
  const a = m.alwaysOverOff;
  log(`'always' / 'off': samples/s ${a.samplesPerSecond.toFixed(3)} (rounds: ${a.perRound.map((r) => r.toFixed(2)).join(' ')})${a.samplesPerWorkerCpuSecond === null ? '' : `, per CPU-s ${a.samplesPerWorkerCpuSecond.toFixed(3)}`}; adapter: ${result.adapter}; ${result.totalSeconds.toFixed(0)} s`);
}
