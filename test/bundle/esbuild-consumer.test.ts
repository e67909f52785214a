// The built package in a browser bundle: a consumer app (test/bundle/consumer) is bundled by
// esbuild from the package as installed (its package.json exports, dist/esm), then run in
// Chromium (SwiftShader WebGPU):
// - on the page, it path traces an emissive quad into a canvas: readPixels and the presented
//   canvas hold the quad's exact sRGB-encoded radiance;
// - in a module Worker given an OffscreenCanvas (transferControlToOffscreen), it path traces the
//   Cornell box: the canvas on the page presents exactly the worker's readPixels.
// The consumer's esbuild configuration needs two entries today, both for lazily loaded code that
// never runs in a browser page here (esm-entry.test.ts checks that they are the only obstacles):
// - `mikktspace`: its wasm-bindgen "bundler" build imports a .wasm file as an ES module, which
//   esbuild cannot bundle (the glTF loader imports it only to generate missing tangents);
// - `node:fs`, `node:path`: @gltf-transform/core's NodeIO imports them dynamically; esbuild's
//   browser platform refuses to resolve them (NodeIO is never used in a browser).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { join } from 'node:path';
import { decode } from 'fast-png';
import type { Browser, Page } from 'playwright-core';
import { chromiumPath, chromiumSkip, chromiumWebGpuArgs } from '../browser/browser-session.ts';
import { linearToSrgb } from '../../src/post/tone-mapping.ts';
import { browserBuildOptions, consumerExternals, createConsumerProject, packageInputs } from './bundle.ts';
import { serveDirectory } from './serve.ts';

const size = 32;

async function openBundledConsumer(t: { after(fn: () => Promise<void> | void): void }, script: string): Promise<{ tab: Page; errors: string[] }> {
  const { build } = await import('esbuild');
  const project = createConsumerProject();
  t.after(() => project.cleanup());
  const outdir = join(project.dir, 'out');
  const result = await build(
    browserBuildOptions(project, {
      entryPoints: ['main.js', 'worker-main.js', 'worker.js'].map((f) => join(project.dir, 'src', f)),
      outdir,
      splitting: true,
      external: consumerExternals,
      metafile: true,
    }),
  );
  assert.deepEqual(result.errors, []);
  const bundledPackage = packageInputs(project, result.metafile!);
  assert.ok(bundledPackage.length > 50, `the bundle holds the package's ESM build (${bundledPackage.length} modules)`);
  const server = await serveDirectory(outdir, `<!doctype html><html><head><meta charset="utf-8"><link rel="icon" href="data:,"><style>html,body{margin:0}canvas{display:block;width:${size}px;height:${size}px}</style></head><body><canvas id="c" width="${size}" height="${size}"></canvas><script type="module" src="/${script}"></script></body></html>`);
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

test('esbuild bundle: a consumer page path traces into a canvas with exact pixels', { skip: chromiumSkip, timeout: 180_000 }, async (t) => {
  const { tab, errors } = await openBundledConsumer(t, 'main.js');
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
});

test('esbuild bundle: a module Worker path traces into an OffscreenCanvas the page presents', { skip: chromiumSkip, timeout: 180_000 }, async (t) => {
  const { tab, errors } = await openBundledConsumer(t, 'worker-main.js');
  const report = await tab.evaluate(
    ({ size }) =>
      (window as unknown as { renderInWorker(c: Element, o: object): Promise<{ inWorker: boolean; samples: number; rays: number; pixels: number[] }> }).renderInWorker(document.getElementById('c')!, { size, samplesPerPixel: 4 }),
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
  assert.deepEqual(errors, []);
});
