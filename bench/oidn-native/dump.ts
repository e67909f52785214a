/**
 * Intel's own Open Image Denoise beside ours (bench/oidn-native/README.md). `dump` renders the
 * denoise bench's scenes (bench/output.ts) at 4, 16 and 64 spp and writes, per scene and sample
 * count, the raw radiance, the albedo, normal and emission AOVs and our WebGPU OIDN's output (f32;
 * `emission: 'exact'` and `'network'`), with a 1024-spp reference (another seed); native.py runs
 * Intel's library on the same inputs; `metrics` scores every image that is there against the
 * reference with the bench's measures.
 *
 *   node bench/oidn-native/dump.ts dump [small]     (after npm run generate)
 *   python bench/oidn-native/native.py
 *   node bench/oidn-native/dump.ts metrics [small]
 *
 * Files: bench/results/oidn-native/<scene>.<spp>.<image>.f32 (RGBA float32, top row first) and
 * <scene>.json (the size).
 */
import { mkdir, mkdtemp, readdir, readFile, rm, writeFile } from 'node:fs/promises';
import { existsSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import type { WavefrontPathTracingOptions } from '../../src/pathtracer/types.ts';
import { displayPeakSignalToNoiseRatio, displayStructuralSimilarity } from '../../src/film/metrics/display.ts';
import { peakSignalToNoiseRatio, relativeMeanSquaredError } from '../../src/film/metrics/image-error.ts';
import { createCornellBoxScene } from '../../src/scene/cornell-box.ts';
import { gltfScene } from '../output.ts';

const dir = fileURLToPath(new URL('../results/oidn-native/', import.meta.url));
const [command, size] = process.argv.slice(2);
const small = size === 'small';
const spps = [4, 16, 64];
type Scene = Partial<WavefrontPathTracingOptions> & { width: number; height: number };

async function scenes(): Promise<[string, Scene][]> {
  const tmp = await mkdtemp(join(tmpdir(), 'oidn-native-'));
  try {
    const gltf = await gltfScene(tmp);
    const [cw, gw, gh] = small ? [96, 128, 96] : [256, 320, 240];
    return [
      [`cornell${cw}`, { ...createCornellBoxScene(), width: cw, height: cw, maxDepth: 6 }],
      [`gltf${gw}`, { ...gltf, width: gw, height: gh }],
    ];
  } finally {
    await rm(tmp, { recursive: true, force: true });
  }
}

async function dump(): Promise<void> {
  await mkdir(dir, { recursive: true });
  const save = (name: string, image: { data: Float32Array }) => writeFile(join(dir, name), image.data);
  for (const [name, scene] of await scenes()) {
    await writeFile(join(dir, `${name}.json`), JSON.stringify({ width: scene.width, height: scene.height }));
    if (!existsSync(join(dir, `${name}.ref.f32`))) {
      const r = await createWavefrontPathTracingComputeRenderer({ ...scene, seed: 1000, tileSize: 256 } as WavefrontPathTracingOptions);
      for (let done = 0; done < 1024; done += 64) await r.renderFrame({ samplesPerPixel: 64 });
      await save(`${name}.ref.f32`, await r.readRadiance());
      r.destroy();
    }
    const exact = await createWavefrontPathTracingComputeRenderer({ ...scene, seed: 5, aovs: true, denoise: { denoiser: 'oidn', precision: 'f32' } } as WavefrontPathTracingOptions);
    const network = await createWavefrontPathTracingComputeRenderer({ ...scene, seed: 5, denoise: { denoiser: 'oidn', precision: 'f32', emission: 'network' } } as WavefrontPathTracingOptions);
    const atrous = await createWavefrontPathTracingComputeRenderer({ ...scene, seed: 5, denoise: 'atrous' } as WavefrontPathTracingOptions);
    let spp = 0;
    for (const target of spps) {
      for (const r of [exact, network, atrous]) await r.renderFrame({ samplesPerPixel: target - spp });
      spp = target;
      const p = `${name}.${spp}`;
      await save(`${p}.color.f32`, await exact.readRadiance());
      for (const aov of ['albedo', 'normal', 'emission'] as const) await save(`${p}.${aov}.f32`, await exact.readAov(aov));
      await save(`${p}.ours_exact.f32`, await exact.readDenoised());
      await save(`${p}.ours_network.f32`, await network.readDenoised());
      await save(`${p}.atrous.f32`, await atrous.readDenoised());
      console.log(`${p}: written`);
    }
    for (const r of [exact, network, atrous]) r.destroy();
  }
}

async function metrics(): Promise<void> {
  const files = await readdir(dir);
  const lum = (d: Float32Array): number => {
    let s = 0;
    for (let i = 0; i < d.length; i += 4) s += 0.2126 * d[i]! + 0.7152 * d[i + 1]! + 0.0722 * d[i + 2]!;
    return s / (d.length / 4);
  };
  for (const [name] of await scenes()) {
    const { width, height } = JSON.parse(await readFile(join(dir, `${name}.json`), 'utf8')) as { width: number; height: number };
    const load = async (f: string) => {
      const b = await readFile(join(dir, f));
      return { width, height, data: new Float32Array(b.buffer.slice(b.byteOffset, b.byteOffset + b.byteLength)) };
    };
    const ref = await load(`${name}.ref.f32`);
    for (const spp of spps) {
      const raw = await load(`${name}.${spp}.color.f32`);
      console.log(`${name} ${spp} spp: display PSNR, linear PSNR (peak 1), SSIM, relMSE, mean vs raw`);
      const skip = new Set(['albedo', 'normal', 'emission', 'pre_albedo', 'pre_normal']);
      for (const f of files.filter((x) => x.startsWith(`${name}.${spp}.`) && !skip.has(x.split('.')[2]!)).sort()) {
        const image = await load(f);
        const label = f.split('.')[2]!;
        console.log(`  ${label.padEnd(28)} ${displayPeakSignalToNoiseRatio(image, ref).toFixed(2)} dB  ${peakSignalToNoiseRatio(image, ref, { peak: 1 }).toFixed(2)} dB  ${displayStructuralSimilarity(image, ref).toFixed(3)}  ${relativeMeanSquaredError(image, ref).toExponential(2)}  ${(100 * (lum(image.data) / lum(raw.data) - 1)).toFixed(2)}%`);
      }
    }
  }
}

if (command === 'dump') await dump();
else if (command === 'metrics') await metrics();
else {
  console.error('usage: node bench/oidn-native/dump.ts dump|metrics [small]');
  process.exit(1);
}
process.exit(0);
