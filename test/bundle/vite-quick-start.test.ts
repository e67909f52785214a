// The README's browser quick start (test/bundle/quick-start: index.html + main.js, the same text)
// in a Vite project that installed the package: Vite serves it from the package's exports (the
// "browser" condition: dist/browser) with no configuration, and Chromium shows the Cornell box
// converging on the canvas.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { cpSync, readFileSync, realpathSync } from 'node:fs';
import { join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { decode } from 'fast-png';
import { chromiumPath, chromiumSkip, chromiumWebGpuArgs } from '../browser/browser-session.ts';
import { createConsumerProject, repoRoot } from './bundle.ts';

test('the README quick start runs unchanged in a Vite project', { skip: chromiumSkip, timeout: 180_000 }, async (t) => {
  const project = await createConsumerProject();
  t.after(() => project.cleanup());
  const app = join(project.dir, 'quick-start');
  cpSync(fileURLToPath(new URL('./quick-start/', import.meta.url)), app, { recursive: true });
  const { createServer } = await import('vite');
  const server = await createServer({
    configFile: false,
    root: app,
    logLevel: 'error',
    server: { host: '127.0.0.1', port: 0, fs: { allow: [project.dir, repoRoot, project.builtDir, project.browserDir] } },
    cacheDir: join(project.dir, '.vite'),
  });
  await server.listen();
  t.after(() => server.close());
  const { chromium } = await import('playwright-core');
  const browser = await chromium.launch({ executablePath: chromiumPath, headless: true, args: chromiumWebGpuArgs });
  t.after(() => browser.close());
  const tab = await browser.newPage({ viewport: { width: 600, height: 600 }, deviceScaleFactor: 1 });
  const errors: string[] = [];
  tab.on('console', (m) => {
    // The browser's own favicon request is not the example's (it names no icon).
    if (m.type() === 'error' && !m.location().url.endsWith('/favicon.ico')) errors.push(m.text());
  });
  tab.on('pageerror', (e) => errors.push(e.message));
  // The quick start's top-level await loop keeps the load event back: wait for the response only.
  await tab.goto(server.resolvedUrls!.local[0]!, { waitUntil: 'commit' });
  // The first frame (1 sample per pixel, a few seconds at 256 x 256 on SwiftShader) is enough to see the walls.
  await tab.waitForFunction(() => /^\d+ samples per pixel/.test(document.querySelector('#samples')?.textContent ?? ''), undefined, { timeout: 120_000 });
  const box = (await tab.locator('#view').boundingBox())!;
  // A clipped page screenshot: an element screenshot would wait for a canvas that keeps repainting to settle.
  const png = decode(await tab.screenshot({ clip: { x: box.x, y: box.y, width: 256, height: 256 }, timeout: 90_000 }));
  assert.deepEqual([png.width, png.height], [256, 256]);
  const channels = png.data.length / (256 * 256);
  const mean = (x0: number, x1: number, y0: number, y1: number): number[] => {
    const sum = [0, 0, 0];
    for (let y = y0; y < y1; y++) for (let x = x0; x < x1; x++) for (let c = 0; c < 3; c++) sum[c] += png.data[(y * 256 + x) * channels + c]!;
    return sum.map((s) => s / ((x1 - x0) * (y1 - y0)));
  };
  // The Cornell box's left wall is red and its right wall green.
  const left = mean(20, 45, 100, 150);
  const right = mean(211, 236, 100, 150);
  assert.ok(left[0]! > 2 * left[1]! && left[0]! > 20, `left wall red: ${left.map(Math.round)}`);
  assert.ok(right[1]! > 1.5 * right[0]! && right[1]! > 20, `right wall green: ${right.map(Math.round)}`);
  assert.deepEqual(errors, []);
  // Vite pre-bundled the package from its browser build (the "browser" export condition).
  const metadata = JSON.parse(readFileSync(join(project.dir, '.vite/deps/_metadata.json'), 'utf8')) as { optimized: Record<string, { src: string }> };
  const src = metadata.optimized['@plasius/gpu-renderer']?.src ?? '';
  assert.ok(realpathSync(resolve(project.dir, '.vite/deps', src)).startsWith(project.browserDir), `Vite's entry: ${src}`);
});
