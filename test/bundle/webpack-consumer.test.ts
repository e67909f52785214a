// The built package in a webpack 5 production build with no configuration that concerns it (entry,
// output folder, and performance hints off so size advice does not count as a warning): the
// consumer app (test/bundle/consumer) is bundled from the package as installed (webpack's web
// target sets the "browser" condition, so its exports pick dist/browser); the Worker is found by
// webpack itself in `new Worker(new URL('./worker.js', import.meta.url))`. Then it runs in Chromium
// with the checks of consumer-page.ts (exact pixels, a normal-mapped glTF whose generated tangents
// equal Node's, a module Worker with an OffscreenCanvas).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { join } from 'node:path';
import type { Configuration, Stats } from 'webpack';
import { chromiumSkip } from '../browser/browser-session.ts';
import { createConsumerProject } from './bundle.ts';
import { checkEmissiveQuad, checkNormalMappedGltf, checkWorker, openConsumerPage } from './consumer-page.ts';

let bundled: Promise<{ outdir: string; modules: string[] }> | undefined;

async function runWebpack(config: Configuration): Promise<Stats> {
  const { default: webpack } = await import('webpack');
  return new Promise((resolve, reject) => {
    webpack(config, (error, stats) => (error || !stats ? reject(error ?? new Error('webpack returned no stats')) : resolve(stats)));
  });
}

/** The consumer bundled once for this file's tests (the project is removed at exit). */
function bundle(): Promise<{ outdir: string; modules: string[] }> {
  bundled ??= (async () => {
    const project = await createConsumerProject();
    process.once('exit', () => project.cleanup());
    const outdir = join(project.dir, 'out');
    const stats = await runWebpack({
      mode: 'production',
      context: project.dir,
      entry: { main: './src/main.js', 'worker-main': './src/worker-main.js' },
      output: { path: outdir, filename: '[name].js' },
      devtool: false,
      performance: { hints: false },
    });
    const info = stats.toJson({ all: false, errors: true, warnings: true, modules: true, nestedModules: true });
    assert.deepEqual((info.errors ?? []).map((e) => e.message), []);
    assert.deepEqual((info.warnings ?? []).map((w) => w.message), []);
    const modules: string[] = [];
    const collect = (list: typeof info.modules): void => {
      for (const m of list ?? []) {
        if (m.nameForCondition) modules.push(m.nameForCondition);
        collect(m.modules);
      }
    };
    collect(info.modules);
    return { outdir, modules: modules.filter((m) => m.startsWith(project.browserDir) || m.startsWith(project.builtDir)).map((m) => (m.startsWith(project.browserDir) ? `browser:${m.slice(project.browserDir.length)}` : `esm:${m.slice(project.builtDir.length)}`)) };
  })();
  return bundled;
}

test('webpack 5 bundles the package for the web with no configuration for it', { timeout: 180_000 }, async () => {
  const { modules } = await bundle();
  assert.ok(modules.filter((m) => m.startsWith('browser:')).length > 50, `the bundle holds the package's browser build (${modules.length} modules)`);
  assert.ok(modules.includes('browser:/vendor/mikktspace.js') && modules.includes('browser:/vendor/gltf-transform-core.js'), 'and its vendored dependencies');
  assert.deepEqual(modules.filter((m) => m.startsWith('esm:')), [], 'no module of dist/esm');
});

test('webpack bundle: a consumer page path traces into a canvas with exact pixels', { skip: chromiumSkip, timeout: 180_000 }, async (t) => {
  const { outdir } = await bundle();
  await checkEmissiveQuad(await openConsumerPage(t, outdir, 'main.js', { module: false }));
});

test('webpack bundle: a normal-mapped glTF without tangents loads with Node\'s MikkTSpace tangents and renders its texels', { skip: chromiumSkip, timeout: 180_000 }, async (t) => {
  const { outdir } = await bundle();
  await checkNormalMappedGltf(await openConsumerPage(t, outdir, 'main.js', { module: false }), outdir);
});

test('webpack bundle: a module Worker path traces into an OffscreenCanvas the page presents', { skip: chromiumSkip, timeout: 180_000 }, async (t) => {
  const { outdir } = await bundle();
  await checkWorker(await openConsumerPage(t, outdir, 'worker-main.js', { module: false }));
});
