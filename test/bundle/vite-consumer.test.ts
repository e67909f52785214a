// The built package in a Vite production build (Rollup) with no configuration that concerns it
// (the entries and their file names only): the consumer app (test/bundle/consumer) from the
// package as installed (Vite resolves the "browser" condition: dist/browser), its Worker found by
// Vite in `new Worker(new URL('./worker.js', import.meta.url))`. In Chromium it passes the glTF and
// Worker checks of consumer-page.ts; vite-quick-start.test.ts covers the dev server.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readdirSync } from 'node:fs';
import { join } from 'node:path';
import type { Logger } from 'vite';
import { chromiumSkip } from '../browser/browser-session.ts';
import { createConsumerProject } from './bundle.ts';
import { checkNormalMappedGltf, checkWorker, openConsumerPage } from './consumer-page.ts';

let bundled: Promise<{ outdir: string }> | undefined;

/** The consumer built once for this file's tests (the project is removed at exit). */
function bundle(): Promise<{ outdir: string }> {
  bundled ??= (async () => {
    const project = await createConsumerProject();
    process.once('exit', () => project.cleanup());
    const outdir = join(project.dir, 'out');
    const { build } = await import('vite');
    const messages: string[] = [];
    const logger: Logger = {
      info: () => {},
      warn: (m) => messages.push(`warning: ${m}`),
      warnOnce: (m) => messages.push(`warning: ${m}`),
      error: (m) => messages.push(`error: ${m}`),
      clearScreen: () => {},
      hasErrorLogged: () => false,
      hasWarned: false,
    };
    await build({
      configFile: false,
      root: project.dir,
      customLogger: logger,
      build: {
        outDir: outdir,
        emptyOutDir: true,
        rollupOptions: { input: { main: join(project.dir, 'src/main.js'), 'worker-main': join(project.dir, 'src/worker-main.js') }, output: { entryFileNames: '[name].js' } },
      },
      // Vite's default worker format (IIFE) cannot split chunks, and the renderer loads the OIDN
      // weights as a chunk on first use: module workers are bundled as ES modules (README, Workers).
      worker: { format: 'es' },
    });
    assert.deepEqual(messages, []);
    // MikkTSpace's WebAssembly travels inside a lazily loaded chunk, not as a .wasm asset.
    assert.deepEqual((readdirSync(outdir, { recursive: true }) as string[]).filter((f) => f.endsWith('.wasm')), []);
    return { outdir };
  })();
  return bundled;
}

test('Vite builds the package for production with no configuration for it but ES-module workers', { timeout: 180_000 }, async () => {
  await bundle();
});

test('Vite build: a normal-mapped glTF without tangents loads with Node\'s MikkTSpace tangents and renders its texels', { skip: chromiumSkip, timeout: 180_000 }, async (t) => {
  const { outdir } = await bundle();
  await checkNormalMappedGltf(await openConsumerPage(t, outdir, 'main.js', { module: true }), outdir);
});

test('Vite build: a module Worker path traces into an OffscreenCanvas the page presents', { skip: chromiumSkip, timeout: 180_000 }, async (t) => {
  const { outdir } = await bundle();
  await checkWorker(await openConsumerPage(t, outdir, 'worker-main.js', { module: true }));
});
