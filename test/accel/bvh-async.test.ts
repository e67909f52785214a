import { after, test } from 'node:test';
import assert from 'node:assert/strict';
import { watchEventLoop } from '../helpers/event-loop.ts';
import { buildBvh, buildBvhAsync, terminateBvhWorkers } from '../../src/accel/bvh-builder.ts';
import { duplicatedSoup, gridMesh, randomSoup } from './bvh-fixtures.ts';

after(() => terminateBvhWorkers());

test('buildBvhAsync produces the same tree as buildBvh', async () => {
  for (const positions of [randomSoup(20000, 51), gridMesh(60), duplicatedSoup(2000, 3, 52)]) {
    const sync = buildBvh(positions);
    const progress: number[] = [];
    const async = await buildBvhAsync(positions, { sliceMs: 1, onProgress: (f) => progress.push(f) });
    assert.equal(async.nodeCount, sync.nodeCount);
    assert.deepEqual(new Uint8Array(async.nodes), new Uint8Array(sync.nodes));
    assert.deepEqual(async.triangleOrder, sync.triangleOrder);
    assert.equal(async.depth, sync.depth);
    assert.equal(async.leafCount, sync.leafCount);
    assert.equal(async.sahCost, sync.sahCost);
    assert.equal(progress.at(-1), 1);
    for (let i = 1; i < progress.length; i++) assert.ok(progress[i]! >= progress[i - 1]!, 'progress never goes back');
  }
});

test('buildBvhAsync on this thread (workers: 0) yields to the event loop during a large build; buildBvh does not', async () => {
  const positions = randomSoup(300000, 53, 100, 1);
  const syncWatch = watchEventLoop();
  const sync = buildBvh(positions);
  const syncSeen = syncWatch.stop();
  assert.equal(syncSeen.turns, 0, 'the synchronous build holds the event loop throughout');

  const asyncWatch = watchEventLoop();
  const result = await buildBvhAsync(positions, { sliceMs: 8, workers: 0 });
  const seen = asyncWatch.stop();
  assert.deepEqual(new Uint8Array(result.nodes), new Uint8Array(sync.nodes));
  assert.ok(seen.turns >= 10, `only ${seen.turns} event-loop turns during a ${sync.buildTimeMs.toFixed(0)} ms build`);
  // Generous bound for a loaded 2-core CI machine; the root split of 300k triangles is the longest slice.
  assert.ok(seen.longestGapMs < 250, `event loop blocked for ${seen.longestGapMs.toFixed(0)} ms`);
  console.log(`# sync ${sync.buildTimeMs.toFixed(0)} ms; async ${result.buildTimeMs.toFixed(0)} ms of work, ${seen.turns} turns, longest block ${seen.longestGapMs.toFixed(1)} ms`);
});

test('buildBvhAsync stops when aborted, on this thread and on workers', async () => {
  const positions = randomSoup(200000, 54, 100, 1);
  for (const workers of [0, 2]) {
    const controller = new AbortController();
    const pending = buildBvhAsync(positions, { sliceMs: 2, workers, signal: controller.signal, onProgress: () => controller.abort(new Error('cancelled by test')) });
    await assert.rejects(pending, /cancelled by test/);
  }
  const already = new AbortController();
  already.abort();
  await assert.rejects(buildBvhAsync(positions, { signal: already.signal }), { name: 'AbortError' });
});
