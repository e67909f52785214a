// The package's browser-facing entries must load in a browser:
// - the ESM entry (dist/esm, Node's "import"): no module it reaches through static `import`
//   statements (its own or its dependencies') may be a Node.js built-in or Node-only Dawn
//   (`webgpu`); Node-only code is reached through dynamic imports only. A static
//   `import … from 'node:…'` once broke browser loading.
// - the browser entry (dist/browser, the "browser" condition): its graph names no Node-only
//   module at all, statically or dynamically, and no .wasm file, so bundlers need no externals;
//   and it exports exactly what the ESM entry exports.
// Checked on the module graphs esbuild resolves for the browser, with a fixture showing that the
// check finds a static Node import two modules deep.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';
import { browserBuildOptions, createConsumerProject, nodeImports, packageInputs, staticNodeImports } from './bundle.ts';

test('the check finds a static node: import deep in a graph and ignores dynamic ones', async (t) => {
  const dir = mkdtempSync(join(tmpdir(), 'esm-entry-fixture-'));
  t.after(() => rmSync(dir, { recursive: true, force: true }));
  writeFileSync(join(dir, 'index.js'), "export { read } from './io.js';\nexport const lazy = () => import('node:path');\n");
  writeFileSync(join(dir, 'io.js'), "import { readFileSync } from 'node:fs';\nexport const read = (p) => readFileSync(p);\n");
  const { edges } = await staticNodeImports(join(dir, 'index.js'));
  assert.deepEqual(
    edges.map((e) => [e.importer.slice(dir.length + 1), e.path, e.kind]),
    [['io.js', 'node:fs', 'import-statement']],
  );
  const all = await nodeImports(join(dir, 'index.js'));
  assert.deepEqual(all.edges.map((e) => [e.path, e.kind]).sort(), [['node:fs', 'import-statement'], ['node:path', 'dynamic-import']]);
});

test('the package ESM entry reaches no Node-only module through static imports', { timeout: 180_000 }, async (t) => {
  const project = await createConsumerProject();
  t.after(() => project.cleanup());
  const { edges, metafile } = await staticNodeImports(project.packageEntry, { absWorkingDir: project.dir, external: ['*.wasm'] });
  const own = packageInputs(project, metafile);
  assert.ok(own.length > 50, `the graph includes the package's modules (${own.length})`);
  assert.ok(Object.keys(metafile.inputs).some((p) => p.includes('@gltf-transform/core')), 'and its dependencies');
  assert.deepEqual(edges, [], 'static imports of Node-only modules');
});

test('the package browser entry names no Node-only module and no .wasm file anywhere in its graph', { timeout: 180_000 }, async (t) => {
  const project = await createConsumerProject();
  t.after(() => project.cleanup());
  const { edges, metafile } = await nodeImports(project.browserEntry, { absWorkingDir: project.dir });
  const own = packageInputs(project, metafile, 'browser');
  assert.ok(own.length > 50, `the graph includes the package's browser modules (${own.length})`);
  assert.ok(own.some((p) => p.endsWith('vendor/gltf-transform-core.js')) && own.some((p) => p.endsWith('vendor/mikktspace.js')), 'and the vendored dependencies');
  assert.ok(Object.keys(metafile.inputs).some((p) => p.includes('node_modules/fflate/')), 'and the shared dependencies from node_modules');
  assert.deepEqual(packageInputs(project, metafile, 'esm'), [], 'no module of dist/esm');
  assert.deepEqual(edges, [], 'imports of Node-only modules');
  assert.deepEqual(Object.keys(metafile.inputs).filter((p) => p.endsWith('.wasm')), [], '.wasm files');
});

test('esbuild resolves the package by name to the browser entry for platform browser', { timeout: 180_000 }, async (t) => {
  const { build } = await import('esbuild');
  const project = await createConsumerProject();
  t.after(() => project.cleanup());
  const result = await build(browserBuildOptions(project, { entryPoints: [join(project.dir, 'src/main.js')], write: false, outdir: join(project.dir, 'out'), splitting: true, metafile: true }));
  assert.deepEqual(result.errors, []);
  assert.deepEqual(result.warnings, []);
  assert.ok(packageInputs(project, result.metafile!, 'browser').length > 50);
  assert.deepEqual(packageInputs(project, result.metafile!, 'esm'), []);
});

test('the browser entry exports exactly the names of the ESM entry', { timeout: 180_000 }, async (t) => {
  const project = await createConsumerProject();
  t.after(() => project.cleanup());
  // Node can load the browser build too (the vendored code touches browser APIs only when used).
  const esm = Object.keys(await import(pathToFileURL(join(project.builtDir, 'index.js')).href)).sort();
  const browser = Object.keys(await import(pathToFileURL(join(project.browserDir, 'index.js')).href)).sort();
  assert.ok(esm.length > 100, `${esm.length} exports`);
  assert.deepEqual(browser, esm);
});
