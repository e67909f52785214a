// A real browser: Debian's Chromium (SwiftShader WebGPU) mounts the wavefront path tracer on a
// canvas. An emissive quad filling the view must present its exact radiance, sRGB-encoded, and the
// presented canvas must equal readPixels() of the same renderer.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { existsSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { decode } from 'fast-png';
import { builtPackageDir } from './built-package.ts';
import { createImportMap } from './import-map.ts';
import { startStaticServer } from './static-server.ts';
import { linearToSrgb } from '../../src/post/tone-mapping.ts';
import type * as Pkg from '../../src/index.ts';

const chromiumPath = '/usr/bin/chromium';
const root = fileURLToPath(new URL('../..', import.meta.url));
const size = 32;

const page = (importMap: object): string => `<!doctype html>
<html><head><meta charset="utf-8">
<script type="importmap">${JSON.stringify(importMap)}</script>
<style>html, body { margin: 0; } canvas { display: block; width: ${size}px; height: ${size}px; }</style>
</head><body><canvas id="pt" width="${size}" height="${size}"></canvas>
<script type="module">
  import * as pkg from '/pkg/index.js';
  window.pkg = pkg;
  window.ready = true;
</script></body></html>`;

test('Chromium: the path tracer presents an emissive quad on a WebGPU canvas exactly', { skip: existsSync(chromiumPath) ? false : `${chromiumPath} is not installed` }, async (t) => {
  const { chromium } = await import('playwright-core');
  const built = builtPackageDir(root);
  t.after(() => built.cleanup());
  const server = await startStaticServer({ root, packageDir: built.dir, page: page(createImportMap(root)) });
  const browser = await chromium.launch({
    executablePath: chromiumPath,
    headless: true,
    args: ['--enable-unsafe-webgpu', '--enable-features=Vulkan', '--use-vulkan=swiftshader', '--use-webgpu-adapter=swiftshader', '--use-angle=swiftshader',
      '--no-sandbox', '--disable-gpu-sandbox', '--disable-background-networking', '--disable-component-update', '--disable-sync', '--no-first-run'],
  });
  t.after(async () => {
    await browser.close();
    await server.close();
  });
  const tab = await browser.newPage({ viewport: { width: 100, height: 100 }, deviceScaleFactor: 1 });
  const pageErrors: string[] = [];
  tab.on('pageerror', (e) => pageErrors.push(e.message));
  await tab.goto(server.url);
  await tab.waitForFunction(() => (window as unknown as { ready?: boolean }).ready === true, undefined, { timeout: 15000 });
  const emission = [0.5, 0.25, 0.05];
  const result = await tab.evaluate(async ({ size, emission }) => {
    const { createWavefrontPathTracingComputeRenderer } = (window as unknown as { pkg: typeof Pkg }).pkg;
    const renderer = await createWavefrontPathTracingComputeRenderer({
      canvas: '#pt', width: size, height: size, maxDepth: 1, samplesPerPixel: 2, toneMapping: 'linear',
      camera: { position: [0, 0, 2], target: [0, 0, 0], fovYDegrees: 40 },
      meshes: [{ positions: [-4, -4, 0, 4, -4, 0, 4, 4, 0, -4, 4, 0], indices: [0, 1, 2, 0, 2, 3], material: { baseColorFactor: [0, 0, 0, 1], emissiveFactor: emission } }],
    });
    const stats = await renderer.renderFrame();
    const pixels = await renderer.readPixels();
    return { samples: stats.samplesAccumulated, pixels: Array.from(pixels.data.slice(0, 4 * size * size)) };
  }, { size, emission });
  assert.deepEqual(pageErrors, []);
  assert.equal(result.samples, 2);
  const expected = emission.map((c) => Math.round(linearToSrgb(c) * 255));
  for (let i = 0; i < size * size; i++) {
    for (let c = 0; c < 3; c++) assert.ok(Math.abs(result.pixels[4 * i + c]! - expected[c]!) <= 1, `readPixels ${i}.${c}: ${result.pixels[4 * i + c]} vs ${expected[c]}`);
  }
  const png = decode(await tab.locator('#pt').screenshot());
  const channels = png.data.length / (png.width * png.height);
  assert.deepEqual([png.width, png.height], [size, size]);
  for (let i = 0; i < size * size; i++) {
    for (let c = 0; c < 3; c++) assert.ok(Math.abs(png.data[i * channels + c]! - expected[c]!) <= 1, `canvas ${i}.${c}: ${png.data[i * channels + c]} vs ${expected[c]}`);
  }
});
