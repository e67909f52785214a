/**
 * Converged references for the browser bench (bench/browser.ts). The furnace's is analytic (a
 * convex Lambertian sphere of albedo a in a uniform environment of radiance 1 reflects exactly a),
 * integrated over each pixel's box footprint. The others are our renderer at high samples per
 * pixel in Node.js (Dawn, whatever adapter it finds), another seed than the measured runs: not
 * independent of our renderer, which bench/browser.ts says in its output, and why it also prints
 * the peer's converged mean beside the reference's.
 *
 * Cached in bench/results/references (git-ignored) as <scene>-<w>x<h>-<spp>spp-<scene hash>.f32 with
 * a .json naming how it was made; a cached reference is reused whatever the renderer's source is
 * now (it is the yardstick, not the thing measured); BENCH_BROWSER_REFERENCE=refresh renders anew.
 */
import { createHash } from 'node:crypto';
import { existsSync } from 'node:fs';
import { mkdir, readFile, writeFile } from 'node:fs/promises';
import { spawnSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';
import { createWavefrontPathTracingComputeRenderer } from '../src/index.ts';
import type { WavefrontPathTracingOptions } from '../src/index.ts';
import { ourSceneOptions, pinholeRay, type BenchScene } from './browser-scenes.ts';

export interface Reference {
  /** Linear RGB, row 0 at the top. */
  rgb: Float32Array;
  source: string;
  /** Seconds spent rendering it now (0: from the cache or analytic). */
  seconds: number;
}

const root = fileURLToPath(new URL('..', import.meta.url));

/** Analytic furnace image: each pixel's box footprint sampled n x n times against the sphere (pinhole camera). */
export function analyticReference(scene: BenchScene, width: number, height: number, n = 8): Float32Array {
  const a = scene.analytic;
  if (!a) throw new Error(`${scene.name} has no analytic answer`);
  const eye = scene.camera.position;
  const ray = pinholeRay(scene.camera, width, height);
  const norm = (p: number[]) => { const l = Math.hypot(...p); return p.map((v) => v / l); };
  const oc = eye.map((e, k) => e - a.sphere.center[k]!);
  const c = oc.reduce((s, v) => s + v * v, 0) - a.sphere.radius ** 2;
  const out = new Float32Array(width * height * 3);
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      let covered = 0;
      for (let j = 0; j < n; j++) {
        for (let i = 0; i < n; i++) {
          const d = norm(ray(x + (i + 0.5) / n, y + (j + 0.5) / n));
          const b = oc.reduce((s, w, k) => s + w * d[k]!, 0);
          if (b * b - c >= 0 && -b - Math.sqrt(b * b - c) > 0) covered++;
        }
      }
      const f = covered / (n * n);
      for (let k = 0; k < 3; k++) out[3 * (y * width + x) + k] = f * a.sphere.value[k]! + (1 - f) * a.background[k]!;
    }
  }
  return out;
}

function git(args: string[]): string {
  const r = spawnSync('git', args, { cwd: root, encoding: 'utf8' });
  return r.status === 0 ? r.stdout.trim() : 'unknown';
}

/** RGBA radiance to RGB. */
export function rgbOf(rgba: ArrayLike<number>): Float32Array {
  const out = new Float32Array((rgba.length / 4) * 3);
  for (let i = 0; i < rgba.length / 4; i++) for (let k = 0; k < 3; k++) out[3 * i + k] = rgba[4 * i + k]!;
  return out;
}

export async function convergedReference(scene: BenchScene, width: number, height: number, spp: number, log: (line: string) => void): Promise<Reference> {
  if (scene.analytic) return { rgb: analyticReference(scene, width, height), source: 'analytic (box-filtered pixel coverage of the ideal sphere)', seconds: 0 };
  const key = createHash('sha256').update(JSON.stringify(scene)).digest('hex').slice(0, 12);
  const base = fileURLToPath(new URL(`./results/references/${scene.name}-${width}x${height}-${spp}spp-${key}`, import.meta.url));
  if (existsSync(`${base}.f32`) && process.env.BENCH_BROWSER_REFERENCE !== 'refresh') {
    const bytes = await readFile(`${base}.f32`);
    const meta = JSON.parse(await readFile(`${base}.json`, 'utf8').catch(() => '{}')) as { source?: string };
    return { rgb: new Float32Array(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength)), source: `${meta.source ?? 'unknown'} (cached)`, seconds: 0 };
  }
  log(`  rendering the ${scene.name} reference: ours, ${spp} spp at ${width}x${height} in Node.js (cached afterwards)`);
  const t0 = performance.now();
  const renderer = await createWavefrontPathTracingComputeRenderer({ ...ourSceneOptions(scene), width, height, seed: 7919, toneMapping: 'linear' } as unknown as WavefrontPathTracingOptions);
  try {
    const perFrame = 16;
    for (let done = 0; done < spp; done += perFrame) await renderer.renderFrame({ samplesPerPixel: Math.min(perFrame, spp - done) });
    const rgb = rgbOf((await renderer.readRadiance()).data);
    const adapter = renderer.getSnapshot().adapter;
    const source = `ours at ${spp} spp, seed 7919, src ${git(['rev-parse', '--short', 'HEAD'])} (${git(['rev-parse', '--short', 'HEAD:src'])} tree), on ${adapter}`;
    await mkdir(fileURLToPath(new URL('./results/references/', import.meta.url)), { recursive: true });
    await writeFile(`${base}.f32`, rgb);
    await writeFile(`${base}.json`, `${JSON.stringify({ scene: scene.name, width, height, spp, source, date: new Date().toISOString() }, null, 2)}\n`);
    return { rgb, source, seconds: (performance.now() - t0) / 1000 };
  } finally {
    renderer.destroy();
  }
}
