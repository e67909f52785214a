// The browser build's vendored dependencies (scripts/browser-build), run in Node against the
// packages they were made from:
// - mikktspace: the inlined WebAssembly, instantiated by `ready()`, gives the Node package's
//   tangents bit for bit, on meshes with random positions, normals and uvs;
// - @gltf-transform/core and /extensions: the copy reads a GLB into the same document as the
//   package does, and only NodeIO (which needs node:fs) fails, with a message saying why.
// The browser tests (esbuild-, webpack-, vite-consumer) check the same tangents in Chromium.
// And its root, split into `export *` over one module per statement of src/index.ts: the same
// names as the ESM root, and a root that is not only named re-exports fails the build.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtempSync, readdirSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';
import { NodeIO, WebIO } from '@gltf-transform/core';
import { ALL_EXTENSIONS } from '@gltf-transform/extensions';
import { builtPackage } from './bundle.ts';
import { splitRootModule } from '../../scripts/browser-build/root.ts';
import { loadGltfScene } from '../../src/io/index.ts';
import { createNormalMappedGlb, meshStreams } from './normal-mapped-asset.ts';

type GenerateTangents = (position: Float32Array, normal: Float32Array, texcoord: Float32Array) => Float32Array;

async function vendored<T>(file: string): Promise<T> {
  const { browserDir } = await builtPackage();
  return (await import(pathToFileURL(join(browserDir, file)).href)) as T;
}

/** A triangle soup (one vertex per corner, as the loader passes it) from a seeded generator. */
function randomCorners(triangles: number, seed: number): { position: Float32Array; normal: Float32Array; texcoord: Float32Array } {
  let state = seed >>> 0;
  const random = (): number => {
    state = (Math.imul(state, 1664525) + 1013904223) >>> 0;
    return state / 2 ** 32;
  };
  const position = Float32Array.from({ length: triangles * 9 }, () => random() * 4 - 2);
  const normal = new Float32Array(triangles * 9);
  for (let v = 0; v < triangles * 3; v++) {
    const n = [random() - 0.5, random() - 0.5, random() + 0.1];
    const len = Math.hypot(n[0]!, n[1]!, n[2]!);
    normal.set(n.map((x) => x / len), v * 3);
  }
  const texcoord = Float32Array.from({ length: triangles * 6 }, () => random());
  return { position, normal, texcoord };
}

test('the vendored mikktspace gives the Node package\'s tangents bit for bit', { timeout: 120_000 }, async () => {
  const browser = await vendored<{ ready(): Promise<void>; generateTangents: GenerateTangents }>('vendor/mikktspace.js');
  const node = (await import('mikktspace')) as { generateTangents: GenerateTangents };
  await browser.ready();
  await browser.ready(); // instantiates once; a second call is the same promise
  for (const [triangles, seed] of [[1, 1], [50, 2], [2000, 3]] as const) {
    const mesh = randomCorners(triangles, seed);
    const expected = node.generateTangents(mesh.position, mesh.normal, mesh.texcoord);
    const actual = browser.generateTangents(mesh.position, mesh.normal, mesh.texcoord);
    assert.equal(expected.length, triangles * 12);
    assert.deepEqual(new Uint32Array(actual.buffer, actual.byteOffset, actual.length), new Uint32Array(expected.buffer, expected.byteOffset, expected.length), `${triangles} triangles`);
  }
});

test('the vendored @gltf-transform reads a GLB as the package does; its NodeIO fails for want of node:fs', { timeout: 120_000 }, async () => {
  const core = await vendored<{ WebIO: typeof WebIO; NodeIO: typeof NodeIO }>('vendor/gltf-transform-core.js');
  const extensions = await vendored<{ ALL_EXTENSIONS: typeof ALL_EXTENSIONS }>('vendor/gltf-transform-extensions.js');
  const glb = await createNormalMappedGlb();
  const viaCopy = new core.WebIO().registerExtensions(extensions.ALL_EXTENSIONS);
  const viaPackage = new WebIO().registerExtensions(ALL_EXTENSIONS);
  const copied = await viaCopy.writeJSON(await viaCopy.readBinary(glb));
  const original = await viaPackage.writeJSON(await viaPackage.readBinary(glb));
  assert.deepEqual(copied.json, original.json);
  assert.deepEqual(copied.resources, original.resources);
  assert.ok((copied.json.meshes ?? []).length === 2);

  const io = new core.NodeIO();
  await assert.rejects(io.init(), /node:(fs|path) is not available in a browser/);
});

test(
  "the browser build's loadGltfScene takes a Document made by the application's own @gltf-transform/core",
  { timeout: 120_000 },
  async () => {
    const { browserDir } = await builtPackage();
    const browser = (await import(pathToFileURL(join(browserDir, 'index.js')).href)) as { loadGltfScene: typeof loadGltfScene };
    const document = await new NodeIO().registerExtensions(ALL_EXTENSIONS).readBinary(await createNormalMappedGlb());
    const reference = await loadGltfScene(document);
    assert.deepEqual(meshStreams((await browser.loadGltfScene(document)).meshes), meshStreams(reference.meshes));
  },
);

test("the browser build's root exports the ESM root's names, each from the same module", { timeout: 120_000 }, async () => {
  const { browserDir, esmDir, report } = await builtPackage();
  const browser = (await import(pathToFileURL(join(browserDir, 'index.js')).href)) as Record<string, unknown>;
  const esm = (await import(pathToFileURL(join(esmDir, 'index.js')).href)) as Record<string, unknown>;
  assert.deepEqual(Object.keys(browser).sort(), Object.keys(esm).sort());
  assert.deepEqual([...report.root.names].sort(), Object.keys(esm).sort());
  // Same code, not copies: each name is the object the module behind it exports.
  const errors = (await import(pathToFileURL(join(browserDir, 'errors/index.js')).href)) as Record<string, unknown>;
  assert.equal(browser.isGpuRendererError, errors.isGpuRendererError);
  assert.ok(report.root.modules.length > 1 && report.root.modules.every((m) => m.startsWith('root/')));
});

test('splitting the root fails on anything but named re-exports', async () => {
  const cases = {
    'a local export': `export const x = 1;\n`,
    'an import': `import { x } from './a/index.js';\nexport { x };\n`,
    'a name exported twice': `export { x } from './a/index.js';\nexport { x } from './b/index.js';\n`,
  };
  for (const [what, source] of Object.entries(cases)) {
    const dir = mkdtempSync(join(tmpdir(), 'gpu-renderer-root-'));
    try {
      writeFileSync(join(dir, 'index.js'), source);
      await assert.rejects(splitRootModule(dir), /index\.js: /, what);
    } finally {
      rmSync(dir, { recursive: true, force: true });
    }
  }
  const dir = mkdtempSync(join(tmpdir(), 'gpu-renderer-root-'));
  try {
    writeFileSync(join(dir, 'index.js'), `// A.\nexport { x, y } from './a/index.js';\n// B.\nexport { z } from './a/index.js';\n`);
    const report = await splitRootModule(dir);
    assert.deepEqual(report, { modules: ['root/a.js', 'root/a-2.js'], names: ['x', 'y', 'z'] });
    assert.deepEqual(readdirSync(join(dir, 'root')).sort(), ['a-2.js', 'a.js']);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});
