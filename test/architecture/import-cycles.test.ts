// No module of src/ or demo/src/ takes part in an import cycle (type imports included: a cycle of
// types is still two modules that cannot be understood one without the other). Shared types belong
// in a module below both.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { fileURLToPath } from 'node:url';
import { importCycles, importGraph } from './import-graph.ts';

const roots = {
  src: fileURLToPath(new URL('../../src/', import.meta.url)),
  'demo/src': fileURLToPath(new URL('../../demo/src/', import.meta.url)),
};

// Cycles that another change of the same reshaping removes. Keep this list short: an entry is a
// debt, not a permission.
const knownCycles: Readonly<Record<keyof typeof roots, readonly string[]>> = {
  src: [],
  'demo/src': [],
};

const cycleKey = (cycle: readonly string[]): string => cycle.join(' <-> ');

for (const [name, root] of Object.entries(roots) as [keyof typeof roots, string][]) {
  test(`import cycles: no module of ${name} imports itself through others`, () => {
    const edges = importGraph(root);
    assert.ok(edges.length > 50, `the import graph of ${name} looks empty (${edges.length} edges)`);
    const found = importCycles(edges).map(cycleKey);
    const allowed = new Set(knownCycles[name]);
    assert.deepEqual(found.filter((key) => !allowed.has(key)), [], `import cycles in ${name}`);
    // An entry whose cycle is gone must leave the list, so the list only ever shrinks.
    assert.deepEqual(knownCycles[name].filter((key) => !found.includes(key)), [], `these known cycles of ${name} no longer exist; remove them from knownCycles`);
  });
}

test('import cycles: the detector finds every strongly connected component and nothing else', () => {
  const edges = [
    // a -> b -> c -> a is one cycle; d hangs off it and e imports itself.
    { from: 'a.ts', to: 'b.ts' },
    { from: 'b.ts', to: 'c.ts' },
    { from: 'c.ts', to: 'a.ts' },
    { from: 'c.ts', to: 'd.ts' },
    { from: 'e.ts', to: 'e.ts' },
    // A diamond is no cycle.
    { from: 'f.ts', to: 'g.ts' },
    { from: 'f.ts', to: 'h.ts' },
    { from: 'g.ts', to: 'i.ts' },
    { from: 'h.ts', to: 'i.ts' },
    // Two cycles joined by a one-way edge stay two.
    { from: 'j.ts', to: 'k.ts' },
    { from: 'k.ts', to: 'j.ts' },
    { from: 'k.ts', to: 'l.ts' },
    { from: 'l.ts', to: 'm.ts' },
    { from: 'm.ts', to: 'l.ts' },
  ];
  assert.deepEqual(importCycles(edges), [['a.ts', 'b.ts', 'c.ts'], ['e.ts'], ['j.ts', 'k.ts'], ['l.ts', 'm.ts']]);
  // A long chain closed at its end is one cycle (the walk is iterative, so depth is no limit).
  const chain = Array.from({ length: 20000 }, (_, i) => ({ from: `n${i}.ts`, to: `n${(i + 1) % 20000}.ts` }));
  assert.equal(importCycles(chain).length, 1);
  assert.equal(importCycles(chain)[0]!.length, 20000);
});
