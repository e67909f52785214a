/**
 * The browser section of `npm run bench` (--browser / --browser-only / BENCH_BROWSER=1): our path
 * tracer and three-gpu-pathtracer (a pinned devDependency) side by side in one headless Chromium
 * (Debian's /usr/bin/chromium; SwiftShader WebGPU with test/browser's flags, or
 * BENCH_BROWSER_GPU=1 for the machine's GPU), on the same scenes (bench/browser-scenes.ts): per
 * scene and renderer, samples per pixel per second and the RMSE of linear radiance against a
 * converged reference (bench/browser-reference.ts) after the same wall-clock budget.
 *
 * Knobs: BENCH_BROWSER_SECONDS (equal-time budget per renderer and scene, default 60),
 * BENCH_BROWSER_SIZE (square image side, default 256), BENCH_BROWSER_SCENES (comma-separated
 * names), BENCH_BROWSER_REFERENCE_SPP (default 512), BENCH_BROWSER_PEER_BUDGET (the peer's path
 * slots per renderSample, default a quarter of the pixels, so one call is a fraction of the budget).
 */
import type { Page } from 'playwright-core';
import { loadavg } from 'node:os';
import { chromiumPath, chromiumWebGpuArgs, openPackagePage } from '../test/browser/browser-session.ts';
import { pageAdapterInfo, runOurs, runPeer, type PageArgs, type PageRun } from './browser-page.ts';
import { convergedReference, type Reference } from './browser-reference.ts';
import { browserBenchScenes, ourSceneOptions, pinholeRay, type BenchScene, type V3 } from './browser-scenes.ts';

export interface BrowserBenchOptions {
  seconds: number;
  size: number;
  referenceSpp: number;
  scenes: string[] | null;
  peerFrameBudget: number | null;
  gpu: boolean;
}

export function browserBenchOptions(env: Readonly<Record<string, string | undefined>>): BrowserBenchOptions {
  const num = (name: string, fallback: number): number => {
    const text = env[name];
    if (text === undefined || text === '') return fallback;
    const n = Number(text);
    if (!(n > 0)) throw new Error(`${name}: expected a positive number, got ${JSON.stringify(text)}`);
    return n;
  };
  return {
    seconds: num('BENCH_BROWSER_SECONDS', 60),
    size: Math.round(num('BENCH_BROWSER_SIZE', 256)),
    referenceSpp: Math.round(num('BENCH_BROWSER_REFERENCE_SPP', 512)),
    scenes: env.BENCH_BROWSER_SCENES ? env.BENCH_BROWSER_SCENES.split(',').map((s) => s.trim()) : null,
    peerFrameBudget: env.BENCH_BROWSER_PEER_BUDGET ? Math.round(num('BENCH_BROWSER_PEER_BUDGET', 1)) : null,
    gpu: env.BENCH_BROWSER_GPU === '1',
  };
}

export interface BrowserRow {
  scene: string;
  renderer: string;
  adapter: string;
  spp: number;
  seconds: number;
  sppPerSecond: number;
  rmse: number;
  mean: V3;
  warmupSeconds: number;
}

export interface BrowserSceneResult {
  scene: string;
  reference: { source: string; mean: V3; seconds: number };
  maskedPixels: number;
  rows: BrowserRow[];
  error?: string;
}

export interface BrowserBenchResult {
  options: BrowserBenchOptions;
  pageAdapter: string;
  chromium: string;
  scenes: BrowserSceneResult[];
  /** 1-minute load average before and after (other processes slow a software adapter). */
  loadAverage: { before: number; after: number };
}

/**
 * Pixels whose footprint (n x n subpixel rays) sees a rectangle light directly. three-gpu-pathtracer
 * skips area lights on camera rays (its LogicKernel tests them only after a bounce) and ours shows
 * them, so both images and the reference leave these pixels out of the means and RMSE.
 */
export function directLightMask(scene: BenchScene, width: number, height: number, n = 4): Uint8Array {
  const mask = new Uint8Array(width * height);
  if (scene.rectLights.length === 0) return mask;
  const eye = scene.camera.position;
  const ray = pinholeRay(scene.camera, width, height);
  const sub = (p: number[], q: number[]) => p.map((v, i) => v - q[i]!);
  const dot = (p: number[], q: number[]) => p.reduce((s, v, i) => s + v * q[i]!, 0);
  const cross = (p: number[], q: number[]) => [p[1]! * q[2]! - p[2]! * q[1]!, p[2]! * q[0]! - p[0]! * q[2]!, p[0]! * q[1]! - p[1]! * q[0]!];
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      let hit = false;
      for (let s = 0; s < n * n && !hit; s++) {
        const d = ray(x + ((s % n) + 0.5) / n, y + (Math.floor(s / n) + 0.5) / n);
        for (const l of scene.rectLights) {
          const normal = cross(l.edgeU, l.edgeV);
          const t = dot(sub(l.center, eye), normal) / dot(d, normal);
          if (!(t > 0)) continue;
          const p = sub(eye.map((e, k) => e + t * d[k]!), l.center);
          // Slightly enlarged, so pixels the light's edge only grazes are out too.
          if (Math.abs(dot(p, l.edgeU)) <= 0.55 * dot(l.edgeU, l.edgeU) && Math.abs(dot(p, l.edgeV)) <= 0.55 * dot(l.edgeV, l.edgeV)) hit = true;
        }
      }
      mask[y * width + x] = hit ? 1 : 0;
    }
  }
  return mask;
}

function meanOf(rgb: ArrayLike<number>, mask: Uint8Array): V3 {
  const sum = [0, 0, 0];
  let count = 0;
  for (let i = 0; i < mask.length; i++) {
    if (mask[i]) continue;
    count++;
    for (let k = 0; k < 3; k++) sum[k] += rgb[3 * i + k]!;
  }
  return sum.map((s) => s / count) as V3;
}

/** Root mean square error over the RGB channels of the unmasked pixels. */
export function rmseOf(rgb: ArrayLike<number>, reference: ArrayLike<number>, mask: Uint8Array): number {
  let sum = 0;
  let count = 0;
  for (let i = 0; i < mask.length; i++) {
    if (mask[i]) continue;
    for (let k = 0; k < 3; k++) {
      const d = rgb[3 * i + k]! - reference[3 * i + k]!;
      sum += d * d;
      count++;
    }
  }
  return Math.sqrt(sum / count);
}

const fmt = (v: V3, digits = 4): string => v.map((c) => c.toFixed(digits)).join(' ');

async function measure(tab: Page, which: 'ours' | 'peer', args: PageArgs & { frameBudget: number }): Promise<PageRun> {
  return which === 'ours' ? tab.evaluate(runOurs, args) : tab.evaluate(runPeer, args);
}

export async function runBrowserBenchmark(options: BrowserBenchOptions, log: (line: string) => void = console.log): Promise<BrowserBenchResult> {
  const { size, seconds } = options;
  const all = browserBenchScenes();
  const scenes = options.scenes ? all.filter((s) => options.scenes!.includes(s.name)) : all;
  if (scenes.length === 0) throw new Error(`BENCH_BROWSER_SCENES names none of ${all.map((s) => s.name).join(', ')}`);
  const session = await openPackagePage({
    style: 'html, body { margin: 0; }',
    body: '',
    viewport: { width: size, height: size },
    imports: {
      three: '/node_modules/three-r185/build/three.module.js',
      'three/webgpu': '/node_modules/three-r185/build/three.webgpu.js',
      'three/tsl': '/node_modules/three-r185/build/three.tsl.js',
      'three/examples/jsm/': '/node_modules/three-r185/examples/jsm/',
      'three-mesh-bvh': '/node_modules/three-mesh-bvh/src/index.js',
      'three-mesh-bvh/webgpu': '/node_modules/three-mesh-bvh/src/webgpu/index.js',
      'three-gpu-pathtracer/webgpu': '/node_modules/three-gpu-pathtracer/src/webgpu/index.js',
    },
    ...(options.gpu ? { args: chromiumWebGpuArgs.filter((a) => !a.includes('swiftshader')) } : {}),
  });
  const result: BrowserBenchResult = { options, pageAdapter: '', chromium: session.browser.version(), scenes: [], loadAverage: { before: loadavg()[0]!, after: 0 } };
  try {
    const { tab } = session;
    tab.setDefaultTimeout(0);
    result.pageAdapter = await tab.evaluate(pageAdapterInfo);
    log(`  Chromium ${result.chromium} (${chromiumPath}), adapter: ${result.pageAdapter}`);
    log(`  ${size}x${size}, ${seconds} s per renderer and scene; references: ${options.referenceSpp} spp unless analytic`);
    for (const scene of scenes) {
      const sceneResult: BrowserSceneResult = { scene: scene.name, reference: { source: '', mean: [0, 0, 0], seconds: 0 }, maskedPixels: 0, rows: [] };
      result.scenes.push(sceneResult);
      try {
        const reference: Reference = await convergedReference(scene, size, size, options.referenceSpp, log);
        const mask = directLightMask(scene, size, size);
        sceneResult.maskedPixels = mask.reduce((s, v) => s + v, 0);
        sceneResult.reference = { source: reference.source, mean: meanOf(reference.rgb, mask), seconds: reference.seconds };
        const args = { scene, ourOptions: ourSceneOptions(scene), width: size, height: size, seconds, seed: 0, frameBudget: options.peerFrameBudget ?? Math.max(1024, Math.round((size * size) / 4)) };
        for (const which of ['ours', 'peer'] as const) {
          const run = await measure(tab, which, args);
          sceneResult.rows.push({
            scene: scene.name, renderer: run.renderer, adapter: run.adapter, spp: run.spp, seconds: run.seconds, sppPerSecond: run.spp / run.seconds,
            rmse: rmseOf(run.rgb, reference.rgb, mask), mean: meanOf(run.rgb, mask), warmupSeconds: run.warmupSeconds,
          });
          log(`  ${scene.name} ${run.renderer}: ${run.spp.toFixed(2)} spp in ${run.seconds.toFixed(1)} s (${run.calls} calls, warm-up ${run.warmupSeconds.toFixed(1)} s)`);
        }
      } catch (error) {
        sceneResult.error = (error as Error).stack ?? String(error);
        log(`  ${scene.name} FAILED: ${(error as Error).message}`);
      }
    }
    if (session.pageErrors.length) log(`  page errors: ${session.pageErrors.join(' | ')}`);
  } finally {
    await session.close();
  }
  result.loadAverage.after = loadavg()[0]!;
  return result;
}

export function printBrowserBenchmark(result: BrowserBenchResult, log: (line: string) => void = console.log): void {
  const rows: Record<string, string | number>[] = [];
  for (const s of result.scenes) {
    const ours = s.rows.find((r) => r.renderer === 'ours');
    const peer = s.rows.find((r) => r.renderer !== 'ours');
    for (const r of s.rows) {
      const other = r === ours ? peer : ours;
      rows.push({
        scene: s.scene,
        renderer: r.renderer,
        'spp/s': Number(r.sppPerSecond.toPrecision(3)),
        spp: Number(r.spp.toFixed(2)),
        seconds: Number(r.seconds.toFixed(1)),
        'RMSE at equal time': Number(r.rmse.toPrecision(3)),
        // ours / peer for spp/s, peer / ours for RMSE: above 1 means ours is ahead.
        'ratio spp/s': r === ours && other ? Number((r.sppPerSecond / other.sppPerSecond).toFixed(2)) : '',
        'ratio RMSE (peer/ours)': r === ours && other ? Number((other.rmse / r.rmse).toFixed(2)) : '',
      });
    }
  }
  console.table(rows);
  for (const s of result.scenes) {
    if (s.error) {
      log(`${s.scene}: FAILED ${s.error.split('\n')[0]}`);
      continue;
    }
    log(`${s.scene}: reference ${s.reference.source}${s.maskedPixels ? `; ${s.maskedPixels} pixels that see the light directly left out` : ''}`);
    log(`  mean RGB  reference ${fmt(s.reference.mean)}`);
    for (const r of s.rows) {
      const rel = r.mean.map((m, k) => (m / s.reference.mean[k]! - 1) * 100);
      log(`  mean RGB  ${r.renderer.padEnd(9)} ${fmt(r.mean)}  (${rel.map((d) => `${d >= 0 ? '+' : ''}${d.toFixed(1)}%`).join(' ')} vs reference)`);
    }
  }
  const adapters = [...new Set(result.scenes.flatMap((s) => s.rows.map((r) => `${r.renderer}: ${r.adapter}`)))];
  log(`adapters: page ${result.pageAdapter}; ${adapters.join('; ')}`);
  log(`load average (1 min) before ${result.loadAverage.before.toFixed(2)}, after ${result.loadAverage.after.toFixed(2)}`);
}
