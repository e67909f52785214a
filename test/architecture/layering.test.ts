// No lower layer imports a higher one (the order is in layers.ts), in the import graph of
// import-graph.ts.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readdirSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import ts from 'typescript';
import { importGraph, type Edge } from './import-graph.ts';
import { layers } from './layers.ts';

const src = fileURLToPath(new URL('../../src/', import.meta.url));

// Upward imports that other changes of the same reshaping remove; each names who removes it. Keep
// this list short: an entry is a debt, not a permission.
const knownUpward: Readonly<Record<string, string>> = {
};

const rank = new Map(layers.flatMap((group, i) => group.map((unit) => [unit, i] as const)));
const units = [...rank.keys()].sort((a, b) => b.length - a.length);

/** Whether `file` is unit `u` or lies inside it; a `*` segment of a unit matches any one segment. */
function contains(u: string, file: string): boolean {
  if (!u.includes('*')) return file === u || file.startsWith(`${u}/`);
  const pattern = u.split('/').map((seg) => (seg === '*' ? '[^/]+' : seg.replace(/[.+?^${}()|[\]\\]/g, '\\$&'))).join('/');
  return new RegExp(`^${pattern}(/|$)`).test(file);
}

/** The unit a src-relative module belongs to (the longest that contains it); null for the entry points in src/ itself. */
function unitOf(file: string): string | null {
  if (!file.includes('/')) return null;
  const unit = units.find((u) => contains(u, file));
  assert.ok(unit, `${file} lies in no unit of test/architecture/layers.ts`);
  return unit;
}

test('layering: every folder of src/ has a layer', () => {
  const folders = readdirSync(src, { withFileTypes: true }).filter((e) => e.isDirectory()).map((e) => e.name);
  const unplaced = folders.filter((f) => !rank.has(f));
  assert.deepEqual(units.filter((u) => !rank.has(u.split('/')[0]!)), [], 'every unit lies in a placed folder');
  assert.deepEqual(unplaced, [], `place these folders in test/architecture/layers.ts: ${unplaced.join(', ')}`);
});

/** The imports from a lower layer into a higher one, as `from -> to` (src-relative). */
function upwardImports(edges: readonly Edge[]): string[] {
  const upward: string[] = [];
  for (const { from, to } of edges) {
    const a = unitOf(from);
    const b = unitOf(to);
    if (a === null || b === null || a === b) continue;
    if (rank.get(a)! < rank.get(b)!) upward.push(`${from} -> ${to}`);
  }
  return upward;
}

test('layering: no module imports a higher layer', () => {
  const edges = importGraph(src);
  assert.ok(edges.length > 500, `the import graph looks empty (${edges.length} edges)`);
  const found = upwardImports(edges);
  const upward = found.filter((key) => !(key in knownUpward));
  assert.deepEqual(upward, [], `imports from a lower layer into a higher one:\n  ${upward.join('\n  ')}`);
  const stillListed = new Set(found.filter((key) => key in knownUpward));
  // An entry whose import is gone must leave the list, so the list only ever shrinks.
  const stale = Object.keys(knownUpward).filter((key) => !stillListed.has(key));
  assert.deepEqual(stale, [], `these allowed upward imports no longer exist; remove them from knownUpward: ${stale.join(', ')}`);
});

test('layering: the rule refuses upward imports and allows downward and entry-point ones', () => {
  const edges: Edge[] = [
    { from: 'scene/scene-file.ts', to: 'io/gltf/index.ts' },
    { from: 'pathtracer/renderer.ts', to: 'scene/types.ts' },
    { from: 'scene/types.ts', to: 'scene/limits.ts' },
    { from: 'index.ts', to: 'cli/main.ts' },
    { from: 'cli/main.ts', to: 'farm/index.ts' },
    // The longest unit decides: the glTF loader sits above the scene, the platform part of io below it.
    { from: 'io/gltf/load-gltf-scene.ts', to: 'io/resource-policy.ts' },
    { from: 'lighting/openexr.ts', to: 'io/resource-policy.ts' },
    { from: 'io/resource-policy.ts', to: 'scene/types.ts' },
  ];
  assert.deepEqual(upwardImports(edges), ['scene/scene-file.ts -> io/gltf/index.ts', 'io/resource-policy.ts -> scene/types.ts']);
  // The pre-processor reports static imports, re-exports and dynamic imports alike.
  const info = ts.preProcessFile("import { x } from '../pathtracer/renderer.ts'; export * from './types.ts'; await import('../io/index.ts');", true, true);
  assert.deepEqual(info.importedFiles.map((f) => f.fileName), ['../pathtracer/renderer.ts', './types.ts', '../io/index.ts']);
});
