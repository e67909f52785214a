// CI's short pass of `npm run fuzz` (scripts/fuzz): a few hundred mutated glTF assets, scene files,
// environment maps and renderer option sets in child processes with time and memory limits and
// escape detection. Every outcome must be a load or a typed error: no untyped error, hang,
// out-of-memory, crash, escape or prototype pollution, and no fault left for the renderer to refuse.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { runFuzz } from '../../scripts/fuzz/run.ts';
import type { Outcome } from '../../scripts/fuzz/outcome.ts';

test('fuzz short pass: 200 glTF, 40 scene, 60 environment-map mutants and 12 option sets', async (t) => {
  const report = await runFuzz({ counts: { gltf: 200, scene: 40, env: 60, options: 12 }, seed: 11, jobs: 2, timeoutMs: 30_000, memoryMb: 2048, out: undefined, log: () => {} });
  t.diagnostic(`\n${report.table}\n${report.outcomes.length} cases in ${report.seconds.toFixed(0)} s`);
  const show = (o: Outcome): string => `${o.kind}:${o.index} ${o.status} ${o.code ?? o.errorName ?? ''} ${o.field ?? ''} ${o.message ?? ''} [${o.notes.join('; ')}] ${(o.escapes ?? []).join(', ')}`;
  assert.deepEqual(report.failures.map(show), []);
  assert.deepEqual(report.unattributedRequests, [], 'requests reached the server no case may contact');
  // Not vacuous: the loaders both load and refuse (the mutants reach past the first check).
  for (const kind of ['gltf', 'scene', 'env'] as const) {
    const mine = report.outcomes.filter((o) => o.kind === kind);
    assert.ok(mine.some((o) => o.status === 'ok'), `${kind}: nothing loaded`);
    assert.ok(mine.some((o) => o.status === 'typed'), `${kind}: nothing refused`);
  }
  assert.ok(report.outcomes.some((o) => o.kind === 'options' && o.status === 'typed'), 'options: nothing refused');
});
