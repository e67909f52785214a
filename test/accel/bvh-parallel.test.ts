import { after, test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';
import { watchEventLoop } from '../helpers/event-loop.ts';
import { buildBvh, buildBvhAsync, buildBvhParallel, terminateBvhWorkers, warmBvhWorkers } from '../../src/accel/bvh-builder.ts';
import { buildOnWorkers } from '../../src/accel/bvh-parallel.ts';
import { resolveBuildParams } from '../../src/accel/bvh-serial.ts';
import { getBvhWorkerPool } from '../../src/accel/bvh-worker-pool.ts';
import { checkInvariants, sameTree } from './bvh-invariants.ts';
import { duplicatedSoup, exponentialSpacing, gridMesh, identicalTriangles, randomSoup } from './bvh-fixtures.ts';

after(() => terminateBvhWorkers());

// Sizes above the top-split threshold (32768 triangles) exercise split jobs, subtree jobs and the
// layout that stitches them; the small ones a single subtree job.
const meshes: Array<[string, Float32Array]> = [
  ['random soup 120k', randomSoup(120_000, 61, 100, 1)],
  ['displaced grid 80k', gridMesh(200)],
  ['duplicated coincident triangles 70k', duplicatedSoup(10_000, 7, 62)],
  ['identical triangles 40k (median splits)', identicalTriangles(40_000)],
  ['exponential spacing 40k (depth budget)', exponentialSpacing(40_000)],
  ['random soup 3k', randomSoup(3000, 63)],
  ['single triangle', randomSoup(1, 64)],
];

for (const [name, positions] of meshes) {
  test(`buildBvhParallel builds the same tree as buildBvh, bit for bit: ${name}`, async () => {
    const serial = buildBvh(positions);
    const parallel = await buildBvhParallel(positions, { workers: 2 });
    assert.ok(sameTree(serial, parallel), 'same nodes, triangle order, depth, leaves and SAH cost');
    // So the parallel tree is valid wherever the serial one is; check it directly all the same.
    checkInvariants(positions, parallel, name.startsWith('identical') || name.startsWith('exponential') ? Infinity : 16);
  });
}

test('the parallel build with the JS loops (wasm: false) gives the same tree', async () => {
  const positions = randomSoup(70_000, 72, 50, 1);
  const js = await buildBvhParallel(positions, { workers: 2, wasm: false });
  assert.ok(sameTree(js, buildBvh(positions)));
});

test('the tree does not depend on the number of workers', async () => {
  const positions = randomSoup(90_000, 65, 50, 1);
  const one = await buildBvhParallel(positions, { workers: 1 });
  const three = await buildBvhParallel(positions, { workers: 3 });
  assert.ok(sameTree(one, three));
  assert.ok(sameTree(one, buildBvh(positions)));
});

test('concurrent parallel builds on the same workers keep to their own meshes', async () => {
  const a = randomSoup(70_000, 74, 50, 1);
  const b = gridMesh(150);
  const [ra, rb] = await Promise.all([buildBvhParallel(a, { workers: 2 }), buildBvhParallel(b, { workers: 2 })]);
  assert.ok(sameTree(ra, buildBvh(a)));
  assert.ok(sameTree(rb, buildBvh(b)));
});

test('without shared memory one worker builds a copy: the same tree', async () => {
  const positions = randomSoup(50_000, 66, 50, 1);
  const pool = await getBvhWorkerPool(1);
  assert.ok(pool, 'workers start in Node');
  const unshared = { ...pool, sharedMemory: false };
  const result = await buildOnWorkers(positions, resolveBuildParams(positions), unshared, { sliceMs: 8 });
  assert.ok(sameTree(buildBvh(positions), result));
});

test('warmBvhWorkers starts the pool, and builds after terminateBvhWorkers start a new one', async () => {
  assert.equal(await warmBvhWorkers(2), true);
  terminateBvhWorkers();
  const positions = randomSoup(40_000, 73, 50, 1);
  assert.ok(sameTree(await buildBvhParallel(positions, { workers: 2 }), buildBvh(positions)));
  assert.equal(await warmBvhWorkers(2), true);
});

test('options and input are validated before any worker starts', async () => {
  await assert.rejects(buildBvhParallel(new Float32Array(10)), RangeError);
  await assert.rejects(buildBvhParallel(randomSoup(4, 1), { workers: -1 }), RangeError);
  await assert.rejects(buildBvhParallel(randomSoup(4, 1), { workers: 1.5 }), RangeError);
  const empty = await buildBvhParallel(new Float32Array(0), { workers: 2 });
  assert.ok(sameTree(empty, buildBvh(new Float32Array(0))));
});

test('progress rises to 1 and a parallel build keeps the event loop turning', async () => {
  const positions = randomSoup(200_000, 67, 100, 1);
  const progress: number[] = [];
  const watch = watchEventLoop();
  const result = await buildBvhParallel(positions, { workers: 2, onProgress: (f) => progress.push(f) });
  const { turns, longestGapMs } = watch.stop();
  assert.ok(sameTree(result, buildBvh(positions)));
  assert.equal(progress.at(-1), 1);
  for (let i = 1; i < progress.length; i++) assert.ok(progress[i]! >= progress[i - 1]!, 'progress never goes back');
  assert.ok(turns >= 10, `only ${turns} event-loop turns`);
  // This thread copies the positions into shared memory, lays out the nodes in slices and evaluates
  // the SAH cost; generous bound for a loaded 2-core machine.
  assert.ok(longestGapMs < 250, `event loop blocked for ${longestGapMs.toFixed(0)} ms`);
});

test('abort stops a parallel build, and the workers serve the next build', async () => {
  const positions = randomSoup(300_000, 68, 100, 1);
  const controller = new AbortController();
  const pending = buildBvhParallel(positions, { workers: 2, signal: controller.signal, onProgress: () => controller.abort(new Error('cancelled by test')) });
  await assert.rejects(pending, /cancelled by test/);
  const early = new AbortController();
  setTimeout(() => early.abort(new Error('early')), 5);
  await assert.rejects(buildBvhParallel(positions, { workers: 2, signal: early.signal }), /early/);
  const aborted = new AbortController();
  aborted.abort();
  await assert.rejects(buildBvhParallel(positions, { signal: aborted.signal }), { name: 'AbortError' });
  const small = randomSoup(60_000, 69, 50, 1);
  assert.ok(sameTree(await buildBvhParallel(small, { workers: 2 }), buildBvh(small)));
});

test('buildBvhAsync takes the worker path for large meshes and gives the same tree', async () => {
  const positions = randomSoup(80_000, 70, 50, 1);
  const viaAsync = await buildBvhAsync(positions);
  const inThread = await buildBvhAsync(positions, { workers: 0 });
  const serial = buildBvh(positions);
  assert.ok(sameTree(viaAsync, serial));
  assert.ok(sameTree(inThread, serial));
});

test('where workers cannot start, the parallel entry points fall back to this thread', () => {
  // Node's permission model without --allow-worker refuses new Worker(): a real "no workers" host.
  const script = fileURLToPath(new URL('./bvh-parallel-no-workers.ts', import.meta.url));
  const run = spawnSync(process.execPath, ['--permission', '--allow-fs-read=*', script], { encoding: 'utf8', timeout: 120_000 });
  assert.equal(run.status, 0, run.stderr);
  const report = JSON.parse(run.stdout.trim().split('\n').at(-1)!) as { pool: boolean; sameParallel: boolean; sameAsync: boolean };
  assert.equal(report.pool, false, 'no worker pool under the permission model');
  assert.ok(report.sameParallel, 'buildBvhParallel fell back to the same tree');
  assert.ok(report.sameAsync, 'buildBvhAsync fell back to the same tree');
});
