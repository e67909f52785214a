// The built package in an esbuild browser bundle with no configuration beyond the platform: a
// consumer app (test/bundle/consumer) is bundled from the package as installed (its package.json
// exports pick dist/browser for the browser), with no externals and no plugins, then run in
// Chromium (checks in consumer-page.ts: exact pixels on a page, a normal-mapped glTF whose
// generated tangents equal Node's, a module Worker with an OffscreenCanvas).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { join } from 'node:path';
import { chromiumSkip } from '../browser/browser-session.ts';
import { browserBuildOptions, createConsumerProject, packageInputs, type ConsumerProject } from './bundle.ts';
import { checkEmissiveQuad, checkNormalMappedGltf, checkWorker, openConsumerPage } from './consumer-page.ts';

let bundled: Promise<{ project: ConsumerProject; outdir: string }> | undefined;

/** The consumer's three entries bundled once for this file's tests (the project is removed at exit). */
function bundle(): Promise<{ project: ConsumerProject; outdir: string }> {
  bundled ??= (async () => {
    const { build } = await import('esbuild');
    const project = await createConsumerProject();
    process.once('exit', () => project.cleanup());
    const outdir = join(project.dir, 'out');
    const result = await build(
      browserBuildOptions(project, {
        entryPoints: ['main.js', 'worker-main.js', 'worker.js'].map((f) => join(project.dir, 'src', f)),
        outdir,
        splitting: true,
        metafile: true,
      }),
    );
    assert.deepEqual(result.errors, []);
    assert.deepEqual(result.warnings, []);
    // The browser condition chose dist/browser: its modules and vendored copies, nothing of dist/esm.
    const browserModules = packageInputs(project, result.metafile!, 'browser');
    assert.ok(browserModules.length > 50, `the bundle holds the package's browser build (${browserModules.length} modules)`);
    assert.ok(browserModules.some((p) => p.endsWith('vendor/mikktspace.js')) && browserModules.some((p) => p.endsWith('vendor/gltf-transform-core.js')), 'and its vendored dependencies');
    assert.deepEqual(packageInputs(project, result.metafile!, 'esm'), [], 'no module of dist/esm');
    assert.ok(!Object.keys(result.metafile!.inputs).some((p) => p.endsWith('.wasm')), 'no .wasm file');
    return { project, outdir };
  })();
  return bundled;
}

test('esbuild bundles the package for the browser with no externals or plugins', { timeout: 180_000 }, async () => {
  await bundle();
});

test('esbuild bundle: a consumer page path traces into a canvas with exact pixels', { skip: chromiumSkip, timeout: 180_000 }, async (t) => {
  const { outdir } = await bundle();
  await checkEmissiveQuad(await openConsumerPage(t, outdir, 'main.js', { module: true }));
});

test('esbuild bundle: a normal-mapped glTF without tangents loads with Node\'s MikkTSpace tangents and renders its texels', { skip: chromiumSkip, timeout: 180_000 }, async (t) => {
  const { outdir } = await bundle();
  await checkNormalMappedGltf(await openConsumerPage(t, outdir, 'main.js', { module: true }), outdir);
});

test('esbuild bundle: a module Worker path traces into an OffscreenCanvas the page presents', { skip: chromiumSkip, timeout: 180_000 }, async (t) => {
  const { outdir } = await bundle();
  await checkWorker(await openConsumerPage(t, outdir, 'worker-main.js', { module: true }));
});
