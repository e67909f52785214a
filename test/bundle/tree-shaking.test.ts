// Tree-shaking of the package root: a browser app that imports one renderer gets that renderer and
// what it needs, not the rest of the package. Each app is bundled from the package as installed
// (minified, code splitting) by Vite (Rollup) and by esbuild, and the modules of the entry chunk
// and of the chunks it imports statically (what the page loads before it runs) are checked by
// path; lazily imported chunks (the OIDN weights, codecs, the glTF reader) are allowed, since the
// app fetches them only on use. The byte budgets catch a regression that keeps the paths but drags
// more code in.
//
// esbuild assigns modules to chunks by following every import statement and every export
// dependency of each module that any entry uses (evanw/esbuild#3531), not the bindings an app
// uses; a root that re-exports by name is such a module in every app, and its export list depends
// on every public name's module, so those that a lazy chunk (the glTF reader) also uses would
// land in a chunk shared with it and loaded at start. The browser build's root therefore reaches
// src/index.ts's statements through `export *` (scripts/browser-build/root.ts), which esbuild
// resolves through; the same budgets hold for both bundlers.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { writeFileSync } from 'node:fs';
import { join, relative, resolve } from 'node:path';
import type { Metafile } from 'esbuild';
import type { Rollup } from 'vite';
import { browserBuildOptions, createConsumerProject, type ConsumerProject } from './bundle.ts';

interface LoadedAtStart {
  /** Minified bytes of the entry chunk and the chunks it imports statically. */
  bytes: number;
  /** Their input modules, as paths inside the package (`dist/browser/...`, `weights/...`) or of dependencies. */
  modules: string[];
  /** Every output chunk's bytes, static or lazy. */
  totalBytes: number;
}

/** A module's path as `dist/browser/...`, `weights/...` (inside the package) or as given (dependencies). */
function packagePath(project: ConsumerProject, path: string): string {
  const real = resolve(project.dir, path);
  for (const [dir, name] of [[project.browserDir, 'dist/browser'], [project.builtDir, 'dist/esm']] as const) if (real.startsWith(dir)) return `${name}${real.slice(dir.length)}`;
  const packageRoot = join(project.dir, 'node_modules/@plasius/gpu-renderer');
  return real.startsWith(packageRoot) ? relative(packageRoot, real) : path;
}

/** What a page that imports `entry` loads before the entry runs (esbuild's metafile). */
function esbuildLoadedAtStart(project: ConsumerProject, metafile: Metafile, entry: string): LoadedAtStart {
  const outputs = metafile.outputs;
  const start = Object.keys(outputs).find((o) => outputs[o]!.entryPoint !== undefined && outputs[o]!.entryPoint!.endsWith(entry));
  assert.ok(start, `no output chunk for ${entry}`);
  const seen = new Set<string>();
  const visit = (output: string): void => {
    if (seen.has(output)) return;
    seen.add(output);
    for (const imp of outputs[output]!.imports) if (imp.kind === 'import-statement' && outputs[imp.path]) visit(imp.path);
  };
  visit(start);
  const modules = [...seen].flatMap((o) => Object.keys(outputs[o]!.inputs)).map((input) => packagePath(project, input));
  const bytes = [...seen].reduce((sum, o) => sum + outputs[o]!.bytes, 0);
  const totalBytes = Object.values(outputs).reduce((sum, o) => sum + o.bytes, 0);
  return { bytes, modules, totalBytes };
}

/** What a page that imports the entry chunk loads before it runs (Rollup's output). */
function rollupLoadedAtStart(project: ConsumerProject, output: Rollup.RollupOutput['output']): LoadedAtStart {
  const chunks = new Map(output.filter((o): o is Rollup.OutputChunk => o.type === 'chunk').map((c) => [c.fileName, c]));
  const entry = [...chunks.values()].find((c) => c.isEntry);
  assert.ok(entry, 'no entry chunk');
  const seen = new Set<string>();
  const visit = (file: string): void => {
    if (seen.has(file) || !chunks.has(file)) return;
    seen.add(file);
    chunks.get(file)!.imports.forEach(visit);
  };
  visit(entry.fileName);
  const size = (c: Rollup.OutputChunk): number => Buffer.byteLength(c.code);
  return {
    bytes: [...seen].reduce((sum, f) => sum + size(chunks.get(f)!), 0),
    modules: [...seen].flatMap((f) => Object.keys(chunks.get(f)!.modules)).map((m) => packagePath(project, m.replace(/^\0/, '').split('?')[0]!)),
    totalBytes: [...chunks.values()].reduce((sum, c) => sum + size(c), 0),
  };
}

const apps: Record<string, string> = {
  'only-path-tracer.js': `import { createWavefrontPathTracingComputeRenderer } from '@plasius/gpu-renderer';\nwindow.create = createWavefrontPathTracingComputeRenderer;\n`,
  'only-raster.js': `import { createRasterRenderer } from '@plasius/gpu-renderer';\nwindow.create = createRasterRenderer;\n`,
  'only-errors.js': `import { isGpuRendererError } from '@plasius/gpu-renderer';\nwindow.check = isGpuRendererError;\n`,
};

type Bundler = 'vite' | 'esbuild';
let bundled: Promise<Record<Bundler, Record<string, LoadedAtStart>>> | undefined;

/** Every app bundled by both bundlers, one build per app so no chunk is shared between apps. */
function bundleApps(): Promise<Record<Bundler, Record<string, LoadedAtStart>>> {
  bundled ??= (async () => {
    const esbuild = await import('esbuild');
    const vite = await import('vite');
    const project = await createConsumerProject();
    process.once('exit', () => project.cleanup());
    const result: Record<Bundler, Record<string, LoadedAtStart>> = { vite: {}, esbuild: {} };
    for (const [file, source] of Object.entries(apps)) {
      const entry = join(project.dir, 'src', file);
      writeFileSync(entry, source);
      const built = (await vite.build({ configFile: false, root: project.dir, logLevel: 'silent', build: { write: false, modulePreload: false, rollupOptions: { input: entry } } })) as Rollup.RollupOutput;
      result.vite[file] = rollupLoadedAtStart(project, built.output);
      const { metafile, errors } = await esbuild.build(browserBuildOptions(project, { entryPoints: [entry], outdir: join(project.dir, 'out', file), splitting: true, minify: true, metafile: true, write: false }));
      assert.deepEqual(errors, []);
      result.esbuild[file] = esbuildLoadedAtStart(project, metafile!, file);
    }
    return result;
  })();
  return bundled;
}

const kib = (bytes: number): string => `${(bytes / 1024).toFixed(1)} KiB`;

/** Modules of `modules` whose path matches `pattern`. */
const matching = (modules: string[], pattern: RegExp): string[] => modules.filter((m) => pattern.test(m));

const notInPathTracerApp = [
  ['the raster renderer', /dist\/browser\/raster\//],
  ['the render farm', /dist\/browser\/farm\/|bullmq|ioredis/],
  ['the CLI', /dist\/browser\/cli\//],
  ['the glTF loader', /dist\/browser\/io\/gltf\/|gltf-transform/],
  ['sequences', /dist\/browser\/sequence\//],
  ['the OIDN weights', /weights\/oidn\//],
] as const;

// Budgets (bytes loaded at start, minified), the same for both bundlers. Measured (2026-11-27,
// this package's browser build, every program group's WGSL in a chunk loaded on first use),
// Vite / esbuild: path tracer 295.5 / 296.0 KiB, raster 195.2 / 198.2 KiB, error helper
// 0.2 / 0.4 KiB (before the curated root: 502.9 / 503.4, 225.0 / 224.7 and 0.2 / 0.4 KiB).
const budgets: Record<string, number> = { 'only-path-tracer.js': 340 * 1024, 'only-raster.js': 230 * 1024, 'only-errors.js': 2 * 1024 };

for (const bundler of ['vite', 'esbuild'] as const) {
  test(`tree-shaking (${bundler}): an app importing only the path tracer loads no raster renderer, farm, CLI, glTF loader, sequences or OIDN weights at start`, { timeout: 300_000 }, async (t) => {
    const app = (await bundleApps())[bundler]['only-path-tracer.js']!;
    t.diagnostic(`only createWavefrontPathTracingComputeRenderer: ${kib(app.bytes)} at start (${app.modules.length} modules), ${kib(app.totalBytes)} with lazy chunks`);
    assert.equal(matching(app.modules, /dist\/browser\/pathtracer\/renderer\.js$/).length, 1, 'the renderer itself is in');
    for (const [what, pattern] of notInPathTracerApp) assert.deepEqual(matching(app.modules, pattern), [], `${what} is not loaded at start`);
    assert.deepEqual(matching(app.modules, /dist\/browser\/animation\//), [], 'animation is not loaded at start');
    assert.ok(app.bytes < budgets['only-path-tracer.js']!, `${kib(app.bytes)} at start exceeds the budget`);
  });

  test(`tree-shaking (${bundler}): an app importing only the raster renderer loads no path tracer, BVH builder or denoiser at start`, { timeout: 300_000 }, async (t) => {
    const app = (await bundleApps())[bundler]['only-raster.js']!;
    t.diagnostic(`only createRasterRenderer: ${kib(app.bytes)} at start (${app.modules.length} modules), ${kib(app.totalBytes)} with lazy chunks`);
    assert.deepEqual(matching(app.modules, /dist\/browser\/pathtracer\/|dist\/browser\/accel\/|weights\/oidn\/|dist\/browser\/film\/denoise\/|dist\/browser\/shaders\/wgsl\/(?!raster\.)/), [], 'no path tracer, BVH builder, denoiser or their WGSL');
    assert.ok(app.bytes < budgets['only-raster.js']!, `${kib(app.bytes)} at start exceeds the budget`);
  });

  test(`tree-shaking (${bundler}): an app importing only an error helper stays small`, { timeout: 300_000 }, async (t) => {
    const app = (await bundleApps())[bundler]['only-errors.js']!;
    t.diagnostic(`only isGpuRendererError: ${kib(app.bytes)} (${app.modules.length} modules)`);
    assert.ok(app.bytes < budgets['only-errors.js']!, `${kib(app.bytes)} for one error helper exceeds the budget`);
  });
}
