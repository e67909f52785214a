// The checks a bundled consumer app (test/bundle/consumer) must pass in Chromium (SwiftShader
// WebGPU), whichever bundler made it (esbuild-consumer.test.ts, webpack-consumer.test.ts):
// - on the page, it path traces an emissive quad into a canvas: readPixels and the presented
//   canvas hold the quad's exact sRGB-encoded radiance;
// - on the page, it loads a normal-mapped .glb without TANGENT (normal-mapped-asset.ts) over
//   fetch: the tangents it generates (MikkTSpace, WebAssembly) equal those Node generates for the
//   same file bit for bit, and the render shows the emissive texture's texels exactly;
// - in a module Worker given an OffscreenCanvas (transferControlToOffscreen), it path traces the
//   Cornell box: the canvas on the page presents exactly the worker's readPixels.
import assert from 'node:assert/strict';
import { writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { decode } from 'fast-png';
import type { Browser, Page } from 'playwright-core';
import { chromiumPath, chromiumWebGpuArgs } from '../browser/browser-session.ts';
import { loadGltfScene } from '../../src/io/index.ts';
import { linearToSrgb } from '../../src/film/tone-mapping.ts';
import { createNormalMappedGlb, meshStreams, panelCamera, panelTexels, type MeshStreams } from './normal-mapped-asset.ts';
import { serveDirectory } from './serve.ts';

export const size = 32;

export interface ConsumerPage {
  tab: Page;
  /** Console errors and uncaught exceptions of the page (and its workers). */
  errors: string[];
}

/**
 * Serves `outdir` with a page holding a `size` x `size` canvas that runs `script` (an ES module,
 * or a classic script when `module` is false), opens it in Chromium and waits for `window.ready`.
 */
export async function openConsumerPage(t: { after(fn: () => Promise<void> | void): void }, outdir: string, script: string, options: { module: boolean }): Promise<ConsumerPage> {
  const type = options.module ? ' type="module"' : '';
  const server = await serveDirectory(
    outdir,
    `<!doctype html><html><head><meta charset="utf-8"><link rel="icon" href="data:,"><style>html,body{margin:0}canvas{display:block;width:${size}px;height:${size}px}</style></head><body><canvas id="c" width="${size}" height="${size}"></canvas><script${type} src="/${script}"></script></body></html>`,
  );
  t.after(() => server.close());
  const { chromium } = await import('playwright-core');
  const browser: Browser = await chromium.launch({ executablePath: chromiumPath, headless: true, args: chromiumWebGpuArgs });
  t.after(() => browser.close());
  const tab = await browser.newPage({ viewport: { width: 100, height: 100 }, deviceScaleFactor: 1 });
  const errors: string[] = [];
  tab.on('console', (m) => {
    if (m.type() === 'error') errors.push(m.text());
  });
  tab.on('pageerror', (e) => errors.push(e.message));
  await tab.goto(server.url);
  await tab.waitForFunction(() => (window as unknown as { ready?: boolean }).ready === true, undefined, { timeout: 30_000 });
  return { tab, errors };
}

async function presented(tab: Page): Promise<{ data: Uint8Array; channels: number }> {
  const png = decode(await tab.locator('#c').screenshot());
  assert.deepEqual([png.width, png.height], [size, size]);
  return { data: png.data as Uint8Array, channels: png.data.length / (size * size) };
}

export async function checkEmissiveQuad({ tab, errors }: ConsumerPage): Promise<void> {
  const emission = [0.6, 0.3, 0.08];
  const result = await tab.evaluate(
    ({ size, emission }) => (window as unknown as { renderEmissiveQuad(c: Element, s: number, e: number[]): Promise<{ samples: number; pixels: number[] }> }).renderEmissiveQuad(document.getElementById('c')!, size, emission),
    { size, emission },
  );
  assert.equal(result.samples, 2);
  const expected = emission.map((c) => Math.round(linearToSrgb(c) * 255));
  const screen = await presented(tab);
  for (let i = 0; i < size * size; i++) {
    for (let c = 0; c < 3; c++) {
      assert.ok(Math.abs(result.pixels[4 * i + c]! - expected[c]!) <= 1, `readPixels ${i}.${c}: ${result.pixels[4 * i + c]} vs ${expected[c]}`);
      assert.ok(Math.abs(screen.data[i * screen.channels + c]! - expected[c]!) <= 1, `canvas ${i}.${c}: ${screen.data[i * screen.channels + c]} vs ${expected[c]}`);
    }
  }
  assert.deepEqual(errors, []);
}

/** Which texel of the 2 x 2 panel texture pixel (x, y) shows, or undefined within 1 pixel of a texel or panel edge. */
function panelTexel(x: number, y: number): number | undefined {
  const half = size / 2;
  const inner = (k: number): boolean => k >= 1 && k <= size - 2 && k !== half - 1 && k !== half;
  if (!inner(x) || !inner(y)) return undefined;
  return (y < half ? 0 : 2) + (x < half ? 0 : 1);
}

export async function checkNormalMappedGltf({ tab, errors }: ConsumerPage, outdir: string): Promise<void> {
  const glb = await createNormalMappedGlb();
  writeFileSync(join(outdir, 'normal-mapped.glb'), glb);
  const node = await loadGltfScene(glb);
  const reference = meshStreams(node.meshes);
  assert.equal(reference.length, 2);
  for (const mesh of reference) assert.equal(mesh.tangents.length, (mesh.positions.length / 3) * 4, 'Node generated a tangent per vertex');
  const patch = reference[1]!.tangents;
  assert.ok(patch.some((v, i) => i % 4 === 0 && Math.abs(v - patch[0]!) > 0.05), 'the patch tangents vary from vertex to vertex');

  const result = await tab.evaluate(
    ({ size, camera }) =>
      (window as unknown as { renderGltf(c: Element, s: number, url: string, camera: object): Promise<{ meshes: MeshStreams[]; samples: number; pixels: number[] }> }).renderGltf(
        document.getElementById('c')!,
        size,
        '/normal-mapped.glb',
        camera,
      ),
    { size, camera: panelCamera },
  );
  // The same vertex streams, tangents included, bit for bit (float32 values survive the JSON trip).
  assert.deepEqual(result.meshes, reference);
  assert.equal(result.samples, 2);
  const screen = await presented(tab);
  let checked = 0;
  for (let y = 0; y < size; y++) {
    for (let x = 0; x < size; x++) {
      const texel = panelTexel(x, y);
      if (texel === undefined) continue;
      const i = y * size + x;
      for (let c = 0; c < 3; c++) {
        const expected = panelTexels[texel]![c]!;
        assert.ok(Math.abs(result.pixels[4 * i + c]! - expected) <= 1, `readPixels (${x}, ${y}).${c}: ${result.pixels[4 * i + c]} vs texel ${texel} ${expected}`);
        assert.ok(Math.abs(screen.data[i * screen.channels + c]! - expected) <= 1, `canvas (${x}, ${y}).${c}: ${screen.data[i * screen.channels + c]} vs texel ${texel} ${expected}`);
      }
      checked++;
    }
  }
  assert.equal(checked, (size - 4) * (size - 4));
  assert.deepEqual(errors, []);
}

export async function checkWorker({ tab, errors }: ConsumerPage): Promise<void> {
  const report = await tab.evaluate(
    ({ size }) =>
      (window as unknown as { renderInWorker(c: Element, o: object): Promise<{ inWorker: boolean; samples: number; rays: number; pixels: number[]; oidn: { denoiser: string; meanRatio: number; changedShare: number } }> }).renderInWorker(document.getElementById('c')!, { size, samplesPerPixel: 4 }),
    { size },
  );
  assert.equal(report.inWorker, true, 'the renderer ran in a worker (no document, importScripts present)');
  assert.equal(report.samples, 4);
  assert.ok(report.rays >= 4 * size * size, `rays traced: ${report.rays}`);
  let mean = 0;
  for (let i = 0; i < size * size; i++) mean += (report.pixels[4 * i]! + report.pixels[4 * i + 1]! + report.pixels[4 * i + 2]!) / 3;
  mean /= size * size;
  assert.ok(mean > 10, `the Cornell box is lit (mean ${mean.toFixed(1)})`);
  // The worker's frame reaches the page's canvas: the presented pixels are its readPixels.
  await tab.waitForTimeout(100);
  const screen = await presented(tab);
  let worst = 0;
  for (let i = 0; i < size * size; i++) for (let c = 0; c < 3; c++) worst = Math.max(worst, Math.abs(screen.data[i * screen.channels + c]! - report.pixels[4 * i + c]!));
  assert.ok(worst <= 1, `presented canvas equals the worker's readPixels within 1 (worst ${worst})`);
  // OIDN ran in the worker: its weights chunk loaded there, the image changed, its energy stayed.
  assert.equal(report.oidn.denoiser, 'oidn');
  assert.ok(report.oidn.changedShare > 0.5, `OIDN changed ${(100 * report.oidn.changedShare).toFixed(0)}% of the pixels`);
  assert.ok(Math.abs(report.oidn.meanRatio - 1) < 0.05, `OIDN kept the mean (ratio ${report.oidn.meanRatio.toFixed(4)})`);
  assert.deepEqual(errors, []);
}
