/**
 * Production-output measurements (adaptive sampling, denoising), separate from the throughput comparison with a
 * baseline: run `BENCH_OUTPUT=1 npm run bench -- --no-baseline --no-bvh` (bench/run.ts calls
 * runOutputBenchmark) or `node bench/output.ts` on its own. Prints tables and writes
 * bench/results/output.json.
 *
 * 1. Adaptive sampling at equal time: a scene of uneven difficulty (open sky, a diffuse floor, a
 *    glossy metal sphere, a diffuse box and the hard shadows of a small bright light) and the
 *    Cornell box, rendered with adaptive sampling until they converge or reach the ceiling, and
 *    uniformly for the same renderFrame time; RMSE, relative MSE and display PSNR against a
 *    converged uniform render.
 * 2. Denoising at 4, 16 and 64 spp on the Cornell box (256x256) and a glTF scene (320x240: textured
 *    floor, boxes, an emissive panel; generated here with glTF-Transform), raw, the a-trous preview
 *    and OIDN: PSNR (display: tone mapped sRGB 8-bit; and linear, peak 1), SSIM (display) and
 *    relative MSE against a converged render, the shift of the image's mean luminance (against the
 *    raw image and the reference), and the time each denoiser takes. The denoisers run in renderers
 *    with the same seed, so they filter the very same raw image.
 *
 * BENCH_OUTPUT_REFERENCE_SPP (default 1024) sets the references' samples per pixel; references are
 * cached in bench/results/references, keyed by the scene, the samples and the renderer's source;
 * BENCH_OUTPUT_ADAPTIVE=0 skips part 1; BENCH_OUTPUT_DENOISE_SIZE=small denoises thumbnails
 * instead (Cornell box 96x96, glTF scene 128x96: smaller than the network's 174-pixel receptive
 * field, where a light's anti-aliased edge is 2 % of the pixels).
 */
import { spawnSync } from 'node:child_process';
import { createHash } from 'node:crypto';
import { existsSync } from 'node:fs';
import { mkdtemp, mkdir, readFile, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { Document, NodeIO } from '@gltf-transform/core';
import { ALL_EXTENSIONS, KHRMaterialsEmissiveStrength } from '@gltf-transform/extensions';
import { encode } from 'fast-png';
import { loadGltfScene } from '../src/io/gltf/load-gltf-scene.ts';
import { createWavefrontPathTracingComputeRenderer } from '../src/pathtracer/index.ts';
import type { WavefrontPathTracingOptions, WavefrontPathTracingRenderer } from '../src/pathtracer/types.ts';
import { displayPeakSignalToNoiseRatio, displayStructuralSimilarity } from '../src/film/metrics/display.ts';
import { peakSignalToNoiseRatio, relativeMeanSquaredError, rootMeanSquaredError } from '../src/film/metrics/image-error.ts';
import { createCornellBoxScene } from '../src/scene/cornell-box.ts';
import type { WavefrontSceneDescription } from '../src/scene/types.ts';

type Scene = Partial<WavefrontPathTracingOptions> & { width: number; height: number };
type Image = { width: number; height: number; data: Float32Array };

const referenceSpp = Number(process.env.BENCH_OUTPUT_REFERENCE_SPP ?? 1024);

/** Open sky, a floor, a glossy metal sphere, a diffuse box and a small bright light: uneven difficulty. */
export function unevenScene(): Scene {
  const quad = (y: number, half: number, flip: boolean) => ({
    positions: [-half, y, half, half, y, half, half, y, -half, -half, y, -half],
    indices: flip ? [0, 2, 1, 0, 3, 2] : [0, 1, 2, 0, 2, 3],
  });
  return {
    width: 128,
    height: 96,
    maxDepth: 6,
    camera: { position: [0, 1.1, 4.2], target: [0, 0.7, 0], up: [0, 1, 0], fovYDegrees: 42 },
    environment: { color: [0.35, 0.45, 0.6] },
    meshes: [
      { ...quad(0, 6, false), material: { baseColorFactor: [0.6, 0.6, 0.6, 1], metallicFactor: 0, roughnessFactor: 1, ior: 1 } },
      { ...quad(3, 0.25, true), material: { baseColorFactor: [0, 0, 0, 1], emissiveFactor: [1, 0.9, 0.8], emissiveStrength: 120 } },
    ],
    sceneObjects: [
      { type: 'sphere', center: [-0.7, 0.6, 0], radius: 0.6, color: [0.95, 0.8, 0.5], metallic: 1, roughness: 0.15 },
      { type: 'box', min: [0.3, 0, -0.4], max: [1.3, 1, 0.6], color: [0.7, 0.25, 0.2], metallic: 0, roughness: 1 },
    ],
  };
}

/** A glTF asset: checkered floor texture, two boxes, an emissive panel and a camera. */
export async function gltfScene(dir: string): Promise<Scene> {
  const doc = new Document();
  const buffer = doc.createBuffer();
  const acc = (type: 'VEC2' | 'VEC3' | 'SCALAR', array: Float32Array<ArrayBuffer> | Uint16Array<ArrayBuffer>) => doc.createAccessor().setType(type).setArray(array).setBuffer(buffer);
  const box = (name: string, color: [number, number, number, number]) => {
    const p: number[] = [];
    const n: number[] = [];
    const idx: number[] = [];
    const faces: [number[], number[], number[]][] = [[[1, 0, 0], [0, 1, 0], [0, 0, 1]], [[-1, 0, 0], [0, 0, 1], [0, 1, 0]], [[0, 1, 0], [0, 0, 1], [1, 0, 0]], [[0, -1, 0], [1, 0, 0], [0, 0, 1]], [[0, 0, 1], [1, 0, 0], [0, 1, 0]], [[0, 0, -1], [0, 1, 0], [1, 0, 0]]];
    for (const [normal, u, v] of faces) {
      const base = p.length / 3;
      for (const [a, b] of [[-1, -1], [1, -1], [1, 1], [-1, 1]]) {
        for (let k = 0; k < 3; k++) p.push(0.5 * (normal[k]! + a! * u[k]! + b! * v[k]!));
        n.push(...normal);
      }
      idx.push(base, base + 1, base + 2, base, base + 2, base + 3);
    }
    const material = doc.createMaterial(name).setBaseColorFactor(color).setMetallicFactor(0).setRoughnessFactor(0.6);
    return doc.createMesh(name).addPrimitive(doc.createPrimitive().setAttribute('POSITION', acc('VEC3', new Float32Array(p))).setAttribute('NORMAL', acc('VEC3', new Float32Array(n))).setIndices(acc('SCALAR', new Uint16Array(idx))).setMaterial(material));
  };
  const texels = new Uint8Array(16 * 16 * 4);
  for (let y = 0; y < 16; y++) for (let x = 0; x < 16; x++) texels.set((x + y) % 2 === 0 ? [200, 190, 170, 255] : [60, 70, 90, 255], 4 * (y * 16 + x));
  const texture = doc.createTexture('checker').setMimeType('image/png').setImage(encode({ width: 16, height: 16, data: texels, channels: 4 }));
  const floorMaterial = doc.createMaterial('floor').setBaseColorTexture(texture).setMetallicFactor(0).setRoughnessFactor(1);
  floorMaterial.getBaseColorTextureInfo()!.setMagFilter(9728);
  const floor = doc.createMesh('floor').addPrimitive(doc.createPrimitive()
    .setAttribute('POSITION', acc('VEC3', new Float32Array([-3, 0, 3, 3, 0, 3, 3, 0, -3, -3, 0, -3])))
    .setAttribute('NORMAL', acc('VEC3', new Float32Array([0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0])))
    .setAttribute('TEXCOORD_0', acc('VEC2', new Float32Array([0, 1, 1, 1, 1, 0, 0, 0])))
    .setIndices(acc('SCALAR', new Uint16Array([0, 1, 2, 0, 2, 3]))).setMaterial(floorMaterial));
  const strength = doc.createExtension(KHRMaterialsEmissiveStrength).createEmissiveStrength().setEmissiveStrength(12);
  const lamp = doc.createMaterial('lamp').setBaseColorFactor([0, 0, 0, 1]).setEmissiveFactor([1, 0.95, 0.85]).setExtension('KHR_materials_emissive_strength', strength);
  const panel = doc.createMesh('panel').addPrimitive(doc.createPrimitive()
    .setAttribute('POSITION', acc('VEC3', new Float32Array([-1, 0, 1, 1, 0, 1, 1, 0, -1, -1, 0, -1])))
    .setIndices(acc('SCALAR', new Uint16Array([0, 2, 1, 0, 3, 2]))).setMaterial(lamp));
  const camera = doc.createCamera('view').setType('perspective').setYFov(0.8).setZNear(0.1);
  const tilt = -0.35;
  doc.createScene()
    .addChild(doc.createNode('floor').setMesh(floor))
    .addChild(doc.createNode('red').setMesh(box('red', [0.75, 0.2, 0.15, 1])).setTranslation([-0.8, 0.5, -0.3]).setRotation([0, Math.sin(0.3), 0, Math.cos(0.3)]))
    .addChild(doc.createNode('blue').setMesh(box('blue', [0.2, 0.35, 0.8, 1])).setTranslation([0.9, 0.35, 0.4]).setScale([0.7, 0.7, 0.7]))
    .addChild(doc.createNode('panel').setMesh(panel).setTranslation([0, 2.6, 0]).setScale([0.8, 1, 0.8]))
    .addChild(doc.createNode('eye').setCamera(camera).setTranslation([0, 1.8, 4.5]).setRotation([Math.sin(tilt / 2), 0, 0, Math.cos(tilt / 2)]));
  const path = join(dir, 'output-bench.glb');
  await writeFile(path, await new NodeIO().registerExtensions(ALL_EXTENSIONS).writeBinary(doc));
  const scene: WavefrontSceneDescription = { ...(await loadGltfScene(path)) };
  return { ...scene, environment: { color: [0.05, 0.06, 0.08] }, width: 128, height: 96, maxDepth: 6 };
}

async function renderer(scene: Scene, options: Partial<WavefrontPathTracingOptions>): Promise<WavefrontPathTracingRenderer> {
  return createWavefrontPathTracingComputeRenderer({ ...scene, ...options } as WavefrontPathTracingOptions);
}

/**
 * The cache key of a reference: the scene, the samples, and the renderer's source as it is now
 * (the committed tree of src/ plus any uncommitted change to it), so a changed renderer renders
 * new references.
 */
function referenceKey(scene: Scene): string {
  const git = (args: string[]) => {
    const r = spawnSync('git', args, { cwd: fileURLToPath(new URL('..', import.meta.url)), encoding: 'utf8', maxBuffer: 1 << 28 });
    return r.status === 0 ? r.stdout : `unavailable ${Math.random()}`;
  };
  const hash = createHash('sha256');
  hash.update(JSON.stringify(scene, (_, v: unknown) => (ArrayBuffer.isView(v) ? Array.from(v as unknown as ArrayLike<number>) : v)));
  hash.update(`${referenceSpp} ${git(['rev-parse', 'HEAD:src'])} ${git(['diff', 'HEAD', '--', 'src'])}`);
  return hash.digest('hex').slice(0, 16);
}

/**
 * A converged render (another seed than the measured ones), cached in bench/results/references
 * (git-ignored) under referenceKey.
 */
async function reference(scene: Scene): Promise<{ image: Image; seconds: number }> {
  const path = fileURLToPath(new URL(`./results/references/${scene.width}x${scene.height}-${referenceSpp}spp-${referenceKey(scene)}.f32`, import.meta.url));
  if (existsSync(path)) {
    const bytes = await readFile(path);
    return { image: { width: scene.width, height: scene.height, data: new Float32Array(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength)) }, seconds: 0 };
  }
  const r = await renderer(scene, { seed: 1000, tileSize: 256 });
  try {
    const t0 = performance.now();
    for (let done = 0; done < referenceSpp; done += 64) await r.renderFrame({ samplesPerPixel: Math.min(64, referenceSpp - done) });
    const image = await r.readRadiance();
    await mkdir(dirname(path), { recursive: true });
    await writeFile(path, image.data);
    return { image, seconds: (performance.now() - t0) / 1000 };
  } finally {
    r.destroy();
  }
}

export interface AdaptiveRow {
  scene: string;
  threshold: number;
  seconds: number;
  adaptiveMeanSpp: number;
  adaptiveMaxSpp: number;
  convergedShare: number;
  uniformSpp: number;
  adaptiveRmse: number;
  uniformRmse: number;
  /** Relative MSE (per-pixel error over reference^2 + 0.01): the adaptive-sampling literature's measure. */
  adaptiveRelativeMse: number;
  uniformRelativeMse: number;
  /** PSNR of the display encodings (exposure, tone mapping, sRGB, 8 bit). */
  adaptiveDisplayPsnr: number;
  uniformDisplayPsnr: number;
}

async function equalTime(name: string, scene: Scene, ref: { image: Image }, threshold: number, ceiling: number): Promise<AdaptiveRow> {
  const a = await renderer(scene, { seed: 7, adaptiveThreshold: threshold, minimumSamplesPerPixel: 8 });
  const u = await renderer(scene, { seed: 8 });
  try {
    let seconds = 0;
    let stats = await a.renderFrame({ samplesPerPixel: 8 });
    seconds += stats.wallTimeMs / 1000;
    while (stats.samplesAccumulated < ceiling && stats.adaptive!.activePixels > 0) {
      stats = await a.renderFrame({ samplesPerPixel: 8 });
      seconds += stats.wallTimeMs / 1000;
    }
    let uniformSeconds = 0;
    let uniformSpp = 0;
    while (uniformSeconds < seconds) {
      const left = (seconds - uniformSeconds) * 1000;
      const s = await u.renderFrame({ samplesPerPixel: 8, frameTimeBudgetMs: left, minimumSamplesPerPixel: 1 });
      uniformSeconds += s.wallTimeMs / 1000;
      uniformSpp = s.samplesAccumulated;
    }
    const ai = await a.readRadiance();
    const ui = await u.readRadiance();
    const ra = rootMeanSquaredError(ai, ref.image);
    const ru = rootMeanSquaredError(ui, ref.image);
    const pixels = scene.width * scene.height;
    return {
      scene: name,
      threshold,
      seconds,
      adaptiveMeanSpp: stats.adaptive!.meanSamplesPerPixel,
      adaptiveMaxSpp: stats.samplesAccumulated,
      convergedShare: stats.adaptive!.convergedPixels / pixels,
      uniformSpp,
      adaptiveRmse: ra,
      uniformRmse: ru,
      adaptiveRelativeMse: relativeMeanSquaredError(ai, ref.image),
      uniformRelativeMse: relativeMeanSquaredError(ui, ref.image),
      adaptiveDisplayPsnr: displayPeakSignalToNoiseRatio(ai, ref.image),
      uniformDisplayPsnr: displayPeakSignalToNoiseRatio(ui, ref.image),
    };
  } finally {
    a.destroy();
    u.destroy();
  }
}

/** The denoisers compared: a-trous, OIDN (default: exact emitters) and, on scenes that show emitters, OIDN denoising them too. */
type Variant = 'atrous' | 'oidn' | 'oidnNetwork';
type Denoised = 'raw' | Variant;
const variantOptions: Record<Variant, WavefrontPathTracingOptions['denoise']> = {
  atrous: 'atrous',
  oidn: 'oidn',
  oidnNetwork: { denoiser: 'oidn', emission: 'network' },
};
const variantLabels: Record<Denoised, string> = { raw: 'raw', atrous: 'a-trous', oidn: 'OIDN', oidnNetwork: "OIDN emission: 'network'" };

export interface DenoiseRow {
  scene: string;
  size: string;
  spp: number;
  variants: Variant[];
  displayPsnr: Partial<Record<Denoised, number>>;
  linearPsnr: Partial<Record<Denoised, number>>;
  ssim: Partial<Record<Denoised, number>>;
  relativeMse: Partial<Record<Denoised, number>>;
  /** Mean luminance against the raw image's, in percent (what the denoiser itself moved). */
  meanShift: Partial<Record<Variant, number>>;
  /** Mean luminance against the reference's, in percent. */
  meanVsReference: Partial<Record<Denoised, number>>;
  /** readDenoised() minus a readback, ms. */
  denoiseMs: Partial<Record<Variant, number>>;
  /** The precision OIDN ran in (the renderer's 'auto': f16 where the device has shader-f16). */
  oidnPrecision: string;
}

const meanLuminance = (image: Image): number => {
  let s = 0;
  for (let i = 0; i < image.data.length; i += 4) s += 0.2126 * image.data[i]! + 0.7152 * image.data[i + 1]! + 0.0722 * image.data[i + 2]!;
  return s / (image.data.length / 4);
};

/** The rows of one scene; every variant renders with the same seed, so all filter the same raw image. */
async function denoiseRows(name: string, scene: Scene, ref: Image, variants: Variant[]): Promise<DenoiseRow[]> {
  const renderers = {} as Record<Variant, WavefrontPathTracingRenderer>;
  for (const v of variants) renderers[v] = await renderer(scene, { seed: 5, denoise: variantOptions[v] });
  const rows: DenoiseRow[] = [];
  try {
    let spp = 0;
    for (const target of [4, 16, 64]) {
      for (const v of variants) await renderers[v].renderFrame({ samplesPerPixel: target - spp });
      spp = target;
      const images: Partial<Record<Denoised, Image>> = { raw: await renderers[variants[0]!].readRadiance() };
      const denoiseMs: Partial<Record<Variant, number>> = {};
      for (const v of variants) {
        const t0 = performance.now();
        images[v] = await renderers[v].readDenoised();
        const withDenoise = performance.now() - t0;
        const t1 = performance.now();
        await renderers[v].readDenoised(); // current now: a readback alone
        denoiseMs[v] = Math.max(0, withDenoise - (performance.now() - t1));
      }
      const per = (f: (image: Image) => number): Partial<Record<Denoised, number>> => Object.fromEntries(Object.entries(images).map(([k, image]) => [k, f(image)]));
      const shift = (a: number, b: number) => 100 * (a / b - 1);
      const rawMean = meanLuminance(images.raw!);
      rows.push({
        scene: name,
        size: `${scene.width}x${scene.height}`,
        spp,
        variants,
        displayPsnr: per((i) => displayPeakSignalToNoiseRatio(i, ref)),
        linearPsnr: per((i) => peakSignalToNoiseRatio(i, ref, { peak: 1 })),
        ssim: per((i) => displayStructuralSimilarity(i, ref)),
        relativeMse: per((i) => relativeMeanSquaredError(i, ref)),
        meanShift: Object.fromEntries(variants.map((v) => [v, shift(meanLuminance(images[v]!), rawMean)])),
        meanVsReference: per((i) => shift(meanLuminance(i), meanLuminance(ref))),
        denoiseMs,
        oidnPrecision: renderers.oidn?.getSnapshot().denoise!.precision ?? 'n/a',
      });
    }
    return rows;
  } finally {
    for (const r of Object.values(renderers)) r.destroy();
  }
}

/** Prints the denoise rows and the goals (OIDN >= 3 dB over a-trous at 4 spp, |mean shift| <= 0.5% at every spp). */
export function printDenoiseRows(rows: readonly DenoiseRow[]): void {
  const f = (v: number | undefined, d = 2) => (v === undefined ? '-' : v.toFixed(d));
  for (const r of rows) {
    const columns: Denoised[] = ['raw', ...r.variants];
    console.log(`  ${r.scene} ${r.size}, ${r.spp} spp (${columns.map((c) => variantLabels[c]).join(' / ')}):`);
    console.log(`    display PSNR ${columns.map((c) => f(r.displayPsnr[c])).join(' / ')} dB; linear PSNR ${columns.map((c) => f(r.linearPsnr[c])).join(' / ')} dB; SSIM ${columns.map((c) => f(r.ssim[c], 3)).join(' / ')}`);
    console.log(`    relMSE ${columns.map((c) => r.relativeMse[c]!.toExponential(2)).join(' / ')}; mean vs raw ${r.variants.map((v) => `${f(r.meanShift[v])}%`).join(' / ')}; mean vs reference ${columns.map((c) => `${f(r.meanVsReference[c])}%`).join(' / ')}`);
    console.log(`    denoise ${r.variants.map((v) => `${f(r.denoiseMs[v], 0)} ms`).join(' / ')} (OIDN in ${r.oidnPrecision})`);
  }
  for (const r of rows) {
    for (const v of r.variants.filter((x) => x !== 'atrous')) {
      const gain = r.displayPsnr[v]! - r.displayPsnr.atrous!;
      const psnrGoal = r.spp === 4 ? ` (>= 3 at 4 spp: ${gain >= 3 ? 'met' : 'NOT met'})` : '';
      console.log(`  goal ${r.scene} ${r.size} ${r.spp} spp, ${variantLabels[v]}: ${f(gain)} dB over a-trous${psnrGoal}, mean shift ${f(r.meanShift[v])}% (within 0.5%: ${Math.abs(r.meanShift[v]!) <= 0.5 ? 'met' : 'NOT met'})`);
    }
  }
}

export async function runOutputBenchmark(): Promise<{ adaptive: AdaptiveRow[]; denoise: DenoiseRow[]; referenceSpp: number; adapter: string }> {
  const dir = await mkdtemp(join(tmpdir(), 'gpu-renderer-output-bench-'));
  try {
    const probe = await renderer({ width: 1, height: 1 }, {});
    const adapter = probe.getSnapshot().adapter;
    probe.destroy();
    console.log(`output bench: references at ${referenceSpp} spp on ${adapter}`);
    const cornell: Scene = { ...createCornellBoxScene(), width: 96, height: 96, maxDepth: 6 };
    const adaptive: AdaptiveRow[] = [];
    const references = new Map<string, { image: Image }>();
    const adaptiveOn = !['0', 'false', 'no', 'off'].includes((process.env.BENCH_OUTPUT_ADAPTIVE ?? '').toLowerCase());
    for (const [name, scene] of adaptiveOn ? ([['uneven scene', unevenScene()], ['Cornell box', cornell]] as const) : []) {
      const ref = await reference(scene);
      references.set(name, ref);
      console.log(`  ${name} reference: ${ref.seconds > 0 ? `${ref.seconds.toFixed(1)} s` : 'cached'}`);
      for (const threshold of [0.05, 0.02]) adaptive.push(await equalTime(name, scene, ref, threshold, 256));
    }
    const e = (v: number) => v.toExponential(2);
    if (adaptive.length > 0) console.table(adaptive.map((r) => ({
      scene: r.scene, threshold: r.threshold, 'time (s)': r.seconds.toFixed(2), 'adaptive spp mean / max': `${r.adaptiveMeanSpp.toFixed(1)} / ${r.adaptiveMaxSpp}`, converged: `${(100 * r.convergedShare).toFixed(0)}%`,
      'uniform spp': r.uniformSpp, 'RMSE adaptive / uniform': `${e(r.adaptiveRmse)} / ${e(r.uniformRmse)}`,
      'relMSE adaptive / uniform': `${e(r.adaptiveRelativeMse)} / ${e(r.uniformRelativeMse)}`,
      'display PSNR adaptive / uniform (dB)': `${r.adaptiveDisplayPsnr.toFixed(2)} / ${r.uniformDisplayPsnr.toFixed(2)}`,
    })));
    // Denoising at sizes people denoise (the thumbnails on request: see the header).
    const small = (process.env.BENCH_OUTPUT_DENOISE_SIZE ?? '').toLowerCase() === 'small';
    const gltf = { ...(await gltfScene(dir)), ...(small ? {} : { width: 320, height: 240 }) };
    const cornellDenoise: Scene = small ? cornell : { ...cornell, width: 256, height: 256 };
    const denoise: DenoiseRow[] = [];
    for (const [name, scene] of [['Cornell box', cornellDenoise], ['glTF scene', gltf]] as const) {
      let ref = scene === cornell ? references.get(name) : undefined;
      if (!ref) {
        const made = await reference(scene);
        console.log(`  ${name} reference: ${made.seconds > 0 ? `${made.seconds.toFixed(1)} s` : 'cached'}`);
        ref = made;
      }
      // The glTF scene shows no emitter, so OIDN's two emission modes give the same image there.
      denoise.push(...(await denoiseRows(name, scene, ref.image, name === 'Cornell box' ? ['atrous', 'oidn', 'oidnNetwork'] : ['atrous', 'oidn'])));
    }
    printDenoiseRows(denoise);
    return { adaptive, denoise, referenceSpp, adapter };
  } finally {
    await rm(dir, { recursive: true, force: true });
  }
}

if (import.meta.url === `file://${process.argv[1]}`) {
  const result = await runOutputBenchmark();
  const out = fileURLToPath(new URL('./results/', import.meta.url));
  await mkdir(out, { recursive: true });
  await writeFile(join(out, 'output.json'), `${JSON.stringify({ date: new Date().toISOString(), ...result }, null, 2)}\n`);
  console.log(`wrote ${join(out, 'output.json')}`);
  process.exit(0);
}
