/**
 * glTF benchmark: how long a large asset takes from file to BVH, and what textures cost per sample.
 *
 * 1. Load + BVH: a deterministic terrain .glb of at least 1M triangles (bench/gltf-assets.ts, with
 *    a 1024^2 PNG texture) is written to a temporary folder, then read with `loadGltfScene(path)`
 *    (file read, GLB and JSON validation, @gltf-transform's reader, accessors to float32 streams,
 *    index range checks, image decoding) and its world-space triangles built into a BVH with
 *    `buildBvhAsync`, the path the renderer takes (shared-memory workers for 50k+ triangles; the
 *    pool is started before timing). Times: the first load of the process (module and decoder
 *    start-up included) on its own, then the median (min-max) of BENCH_GLTF_RUNS (3) loads and
 *    builds. Triangles/s = triangles / (median load + median BVH).
 * 2. Textures: a textured room (base colour, metallic-roughness and normal maps, one repeated by
 *    KHR_texture_transform) rendered at BENCH_GLTF_SIZE^2 (256), maxDepth 8, BENCH_GLTF_SPP (8) spp
 *    per timed frame, beside the same loaded scene with every texture replaced by its mean value
 *    (withTexturesAveraged: the surfaces reflect as much light, so paths are as long, and the
 *    kernels compile without texture sampling). Both renderers live on one device; after one
 *    untimed warm-up frame each, their timed frames alternate for BENCH_GLTF_ROUNDS (3) rounds.
 *    Samples/s, rays/s and, on CPU adapters, samples per CPU-second of the driver's threads
 *    (cpu-clock.ts).
 *
 * bench/run.ts runs this in a child process (gltf-child.ts); `node bench/gltf-child.ts` runs it alone.
 */
import { mkdtemp, rm, stat, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { NodeIO } from '@gltf-transform/core';
import { ALL_EXTENSIONS } from '@gltf-transform/extensions';
import { buildBvhAsync, terminateBvhWorkers, warmBvhWorkers } from '../src/accel/bvh-builder.ts';
import { loadGltfScene, type GltfScene } from '../src/io/index.ts';
import { createWavefrontPathTracingComputeRenderer } from '../src/pathtracer/index.ts';
import type { WavefrontPathTracingRenderer } from '../src/pathtracer/types.ts';
import { srgbToLinear } from '../src/color/srgb.ts';
import type { WavefrontImageInput, WavefrontMaterialInput, WavefrontSceneDescription, WavefrontTextureRefInput } from '../src/scene/types.ts';
import { terrainGlb, texturedRoomDocument } from './gltf-assets.ts';
import { isCpuAdapter } from './cpu-clock.ts';
import { roundFigures, spread, timedRounds, type RoundRow, type Spread } from './timed-rounds.ts';

export { spread, type Spread } from './timed-rounds.ts';

export interface GltfLoadResult {
  triangles: number;
  vertices: number;
  fileBytes: number;
  runs: number;
  /** The first loadGltfScene of the process, ms (module and decoder start-up included). */
  firstLoadMs: number;
  loadMs: Spread;
  bvhMs: Spread;
  bvhWorkers: number;
  /** triangles / (median load + median BVH), per second. */
  trianglesPerSecond: number;
  /** BVH nodes and SAH cost of the last build, for checking that runs built the same tree. */
  bvhNodes: number;
  sahCost: number;
}

export interface GltfRenderRow extends RoundRow {
  scene: string;
  triangles: number;
  textures: number;
  textureBytes: number;
}

export interface GltfBenchResult {
  name: 'gltf';
  node: string;
  adapter: string;
  load: GltfLoadResult;
  render: {
    rows: GltfRenderRow[];
    rounds: number;
    maxDepth: number;
    /** Textured over averaged, of the medians; and of samples/s within each round. */
    texturedOverAveraged: { samplesPerSecond: number; raysPerSecond: number; perRoundSamplesPerSecond: number[] };
  };
  totalSeconds: number;
}

export function envInteger(name: string, fallback: number): number {
  const n = Number(process.env[name]);
  return Number.isInteger(n) && n > 0 ? n : fallback;
}

/** World-space triangles (9 floats each) of a loaded scene's instances, as the renderer flattens them. */
function worldTriangles(scene: GltfScene): Float32Array {
  let count = 0;
  for (const inst of scene.instances) count += (scene.meshes[inst.mesh]!.indices?.length ?? 0) / 3;
  const out = new Float32Array(count * 9);
  let o = 0;
  for (const inst of scene.instances) {
    const mesh = scene.meshes[inst.mesh]!;
    const p = mesh.positions;
    const m = inst.transform ?? [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];
    const indices = mesh.indices!;
    for (let i = 0; i < indices.length; i++) {
      const v = indices[i]!;
      const x = p[3 * v]!, y = p[3 * v + 1]!, z = p[3 * v + 2]!;
      out[o++] = m[0]! * x + m[4]! * y + m[8]! * z + m[12]!;
      out[o++] = m[1]! * x + m[5]! * y + m[9]! * z + m[13]!;
      out[o++] = m[2]! * x + m[6]! * y + m[10]! * z + m[14]!;
    }
  }
  return out;
}

async function measureLoad(log: (line: string) => void): Promise<GltfLoadResult> {
  const target = envInteger('BENCH_GLTF_TRIANGLES', 1_000_000);
  const runs = envInteger('BENCH_GLTF_RUNS', 3);
  const dir = await mkdtemp(join(tmpdir(), 'gpu-renderer-bench-gltf-'));
  try {
    const asset = await terrainGlb(target);
    const path = join(dir, 'terrain.glb');
    await writeFile(path, asset.glb);
    const fileBytes = (await stat(path)).size;
    log(`  terrain.glb: ${asset.triangles.toLocaleString('en-US')} triangles, ${asset.vertices.toLocaleString('en-US')} vertices, ${(fileBytes / 2 ** 20).toFixed(1)} MiB`);
    const workers = Math.max(1, Math.min(8, navigator.hardwareConcurrency || 2));
    await warmBvhWorkers(workers);
    let t0 = performance.now();
    let scene = await loadGltfScene(path);
    const firstLoadMs = performance.now() - t0;
    const load: number[] = [];
    const bvh: number[] = [];
    let last = { nodeCount: 0, sahCost: 0 };
    for (let r = 0; r < runs; r++) {
      t0 = performance.now();
      scene = await loadGltfScene(path);
      load.push(performance.now() - t0);
      const triangles = worldTriangles(scene);
      t0 = performance.now();
      last = await buildBvhAsync(triangles, { workers });
      bvh.push(performance.now() - t0);
      log(`  run ${r + 1}/${runs}: load ${load[r]!.toFixed(0)} ms, BVH ${bvh[r]!.toFixed(0)} ms`);
    }
    const loadMs = spread(load);
    const bvhMs = spread(bvh);
    return {
      triangles: asset.triangles, vertices: asset.vertices, fileBytes, runs, firstLoadMs, loadMs, bvhMs, bvhWorkers: workers,
      trianglesPerSecond: asset.triangles / ((loadMs.median + bvhMs.median) / 1000), bvhNodes: last.nodeCount, sahCost: last.sahCost,
    };
  } finally {
    terminateBvhWorkers();
    await rm(dir, { recursive: true, force: true });
  }
}

/** Mean of an RGBA8 image per channel, rgb decoded from sRGB first when `srgb`. */
function imageMean(image: WavefrontImageInput, srgb: boolean): [number, number, number, number] {
  const sum = [0, 0, 0, 0];
  const texels = image.width * image.height;
  for (let t = 0; t < texels; t++) {
    for (let c = 0; c < 4; c++) {
      const v = image.data[4 * t + c]! / 255;
      sum[c] += srgb && c < 3 ? srgbToLinear(v) : v;
    }
  }
  return sum.map((v) => v / texels) as [number, number, number, number];
}

/**
 * The same scene with every texture replaced by its mean: base colour and emissive factors times
 * their texture's mean (in linear light), roughness and metallic times the mean of G and B; normal
 * and occlusion maps dropped. The surfaces reflect about as much light as with their textures, so
 * paths are about as long, and what differs is the cost of sampling textures (and the kernels
 * compiled with texture sampling switched on).
 */
export function withTexturesAveraged(scene: WavefrontSceneDescription): WavefrontSceneDescription {
  const images = scene.images ?? [];
  const textures = scene.textures ?? [];
  const mean = (ref: WavefrontTextureRefInput | undefined, srgb: boolean): [number, number, number, number] => {
    if (ref === undefined) return [1, 1, 1, 1];
    const image = textures[ref.index]!.image;
    return imageMean(typeof image === 'number' ? images[image]! : image, srgb);
  };
  const materials = (scene.materials ?? []).map((m): WavefrontMaterialInput => {
    const out = Object.fromEntries(Object.entries(m).filter(([key]) => !key.endsWith('Texture'))) as WavefrontMaterialInput;
    const base = mean(m.baseColorTexture, true);
    const factor = m.baseColorFactor ?? [1, 1, 1, 1];
    out.baseColorFactor = [0, 1, 2, 3].map((c) => (factor[c] ?? 1) * base[c]!);
    const mr = mean(m.metallicRoughnessTexture, false);
    out.roughnessFactor = (m.roughnessFactor ?? 1) * mr[1];
    out.metallicFactor = (m.metallicFactor ?? 1) * mr[2];
    const glow = mean(m.emissiveTexture, true);
    if (m.emissiveFactor) out.emissiveFactor = m.emissiveFactor.map((f, c) => f * glow[c]!);
    return out;
  });
  return { ...scene, materials, textures: [], images: [] };
}

async function measureTextures(log: (line: string) => void): Promise<{ rows: GltfRenderRow[]; rounds: number; ratios: GltfBenchResult['render']['texturedOverAveraged']; adapter: string }> {
  const size = envInteger('BENCH_GLTF_SIZE', 256);
  const spp = envInteger('BENCH_GLTF_SPP', 8);
  const rounds = envInteger('BENCH_GLTF_ROUNDS', 3);
  const glb = await new NodeIO().registerExtensions(ALL_EXTENSIONS).writeBinary(texturedRoomDocument());
  const textured = { ...(await loadGltfScene(glb)) };
  const variants: Array<{ scene: string; description: WavefrontSceneDescription }> = [
    { scene: 'textured room', description: textured },
    { scene: 'same room, textures averaged', description: withTexturesAveraged(textured) },
  ];
  const renderers: WavefrontPathTracingRenderer[] = [];
  try {
    for (const v of variants) {
      const renderer = await createWavefrontPathTracingComputeRenderer({ ...v.description, width: size, height: size, maxDepth: 8, samplesPerPixel: 1 });
      renderers.push(renderer);
      await renderer.renderFrame({ samplesPerPixel: 1 }); // warm-up: pipelines compile on first use
    }
    const figures = await timedRounds(renderers, size * size, spp, rounds, (r, samples) => {
      log(`  round ${r + 1}/${rounds}: ${variants.map((v, k) => `${v.scene} ${(samples[k]![r]! / 1e6).toFixed(3)} M samples/s`).join(', ')}`);
    });
    const adapter = renderers[0]!.getSnapshot().adapter;
    const cpu = isCpuAdapter(adapter);
    const rows = variants.map((v, k): GltfRenderRow => {
      const snapshot = renderers[k]!.getSnapshot();
      return {
        scene: v.scene, triangles: snapshot.triangleCount, textures: snapshot.textureCount, textureBytes: snapshot.memory.textureBytes,
        ...roundFigures(figures, k, cpu, size, spp),
      };
    });
    const ratios = {
      samplesPerSecond: rows[0]!.samplesPerSecond.median / rows[1]!.samplesPerSecond.median,
      raysPerSecond: rows[0]!.raysPerSecond.median / rows[1]!.raysPerSecond.median,
      perRoundSamplesPerSecond: figures.samples[0]!.map((v, r) => v / figures.samples[1]![r]!),
    };
    return { rows, rounds, ratios, adapter };
  } finally {
    for (const renderer of renderers) renderer.destroy();
  }
}

export async function runGltfBenchmark(options: { log?: (line: string) => void } = {}): Promise<GltfBenchResult> {
  const log = options.log ?? ((line: string) => console.log(line));
  const began = performance.now();
  log('  load + BVH');
  const load = await measureLoad(log);
  log('  textures');
  const textures = await measureTextures(log);
  return {
    name: 'gltf',
    node: process.version,
    adapter: textures.adapter,
    load,
    render: { rows: textures.rows, rounds: textures.rounds, maxDepth: 8, texturedOverAveraged: textures.ratios },
    totalSeconds: (performance.now() - began) / 1000,
  };
}

/** The result as printed tables (bench/run.ts and gltf-child.ts). */
export function printGltfResult(result: GltfBenchResult, print: (value: unknown) => void = console.table, log: (line: string) => void = console.log): void {
  const l = result.load;
  const ms = (s: Spread): string => `${s.median.toFixed(0)} (${s.min.toFixed(0)}-${s.max.toFixed(0)})`;
  print([{
    triangles: l.triangles, 'file MiB': Number((l.fileBytes / 2 ** 20).toFixed(1)), 'first load ms': Math.round(l.firstLoadMs),
    'load ms': ms(l.loadMs), [`BVH ms (${l.bvhWorkers} workers)`]: ms(l.bvhMs), 'M triangles/s (load + BVH)': Number((l.trianglesPerSecond / 1e6).toFixed(2)), runs: l.runs,
  }]);
  const mega = (s: Spread | null): string => (s === null ? '' : `${(s.median / 1e6).toFixed(3)} (${(s.min / 1e6).toFixed(3)}-${(s.max / 1e6).toFixed(3)})`);
  print(result.render.rows.map((r) => ({
    scene: r.scene, triangles: r.triangles, textures: r.textures, 'texture MiB': Number((r.textureBytes / 2 ** 20).toFixed(2)), size: r.resolution, spp: r.spp,
    'M samples/s': mega(r.samplesPerSecond), 'M rays/s': mega(r.raysPerSecond), 'M samples/CPU-s': mega(r.samplesPerWorkerCpuSecond),
    'other load (cores)': r.otherLoadCores ? `${r.otherLoadCores.median.toFixed(2)} (max ${r.otherLoadCores.max.toFixed(2)})` : '',
  })));
  const ratio = result.render.texturedOverAveraged;
  log(`textured / averaged: samples/s ${ratio.samplesPerSecond.toFixed(3)} (rounds: ${ratio.perRoundSamplesPerSecond.map((r) => r.toFixed(2)).join(' ')}), rays/s ${ratio.raysPerSecond.toFixed(3)}; adapter: ${result.adapter}`);
}
