// Child process of bvh-parallel.test.ts, run under Node's permission model without --allow-worker:
// workers cannot start, so both parallel entry points must fall back to the calling thread.
import { buildBvh, buildBvhAsync, buildBvhParallel } from '../../src/accel/bvh-builder.ts';
import { getBvhWorkerPool, warmBvhWorkers } from '../../src/accel/bvh-worker-pool.ts';
import { sameTree } from './bvh-invariants.ts';
import { randomSoup } from './bvh-fixtures.ts';

const positions = randomSoup(60_000, 71, 50, 1);
const pool = await getBvhWorkerPool(2);
const serial = buildBvh(positions);
const parallel = await buildBvhParallel(positions, { workers: 2 });
const viaAsync = await buildBvhAsync(positions, { workers: 2 });
const warmed = await warmBvhWorkers(2);
console.log(JSON.stringify({ pool: pool !== null || warmed, sameParallel: sameTree(serial, parallel), sameAsync: sameTree(serial, viaAsync) }));
