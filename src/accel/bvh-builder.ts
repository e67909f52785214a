/**
 * CPU BVH construction: top-down binned SAH after Wald, "On fast construction of SAH-based bounding
 * volume hierarchies" (IEEE RT 2007), flattened into the `bvhNodeLayout` records the WGSL traversal
 * (`bvh-traversal.wgsl`) walks with a fixed 64-entry stack.
 *
 * Layout: nodes are allocated in sibling pairs, so an interior node's children always sit at
 * `leftOrFirst` and `leftOrFirst + 1` (one index per interior node, both child boxes fetched
 * together, as in the layout of Aila & Laine, "Understanding the efficiency of ray traversal on
 * GPUs", HPG 2009). Subtrees are emitted depth first (left subtree before right), so a subtree is
 * roughly contiguous in memory. Node 0 is the root.
 *
 * Three entry points build the same tree, bit for bit (bvh-kernels.ts holds the one algorithm):
 * - `buildBvh`: synchronous, on the calling thread;
 * - `buildBvhParallel`: on a pool of inline Workers sharing memory (bvh-parallel.ts);
 * - `buildBvhAsync`: the parallel build where Workers are available and the mesh is large enough,
 *   otherwise the single-threaded build in time slices that yield to the event loop.
 */
import type { BvhAsyncBuildOptions, BvhBuildOptions, BvhBuildResult } from './bvh-build-types.ts';
import { buildOnWorkers } from './bvh-parallel.ts';
import { createSerialBuildState, emptySceneResult, eventLoopYield, resolveBuildParams } from './bvh-serial.ts';
import { defaultBvhWorkerCount, getBvhWorkerPool } from './bvh-worker-pool.ts';

export type { BvhAsyncBuildOptions, BvhBuildOptions, BvhBuildResult } from './bvh-build-types.ts';
export { BVH_MAX_DEPTH, BVH_NODE_BYTES } from './bvh-serial.ts';
export { terminateBvhWorkers, warmBvhWorkers } from './bvh-worker-pool.ts';

/**
 * Below this many triangles `buildBvhAsync` builds on the calling thread by default: the whole
 * build then takes about as long as handing the mesh to workers and back.
 */
export const BVH_PARALLEL_MIN_TRIANGLES = 50_000;

/**
 * Builds the BVH synchronously on the calling thread. On the main thread of a browser this blocks
 * for the whole build (about a second per million triangles); prefer `buildBvhAsync` for large meshes.
 */
export function buildBvh(positions: Float32Array, options?: BvhBuildOptions): BvhBuildResult {
  const state = createSerialBuildState(positions, resolveBuildParams(positions, options), options?.wasm ?? true);
  state.step(Infinity);
  return state.finish();
}

async function buildTimeSliced(positions: Float32Array, options: BvhAsyncBuildOptions): Promise<BvhBuildResult> {
  const { sliceMs = 8, signal, onProgress } = options;
  const state = createSerialBuildState(positions, resolveBuildParams(positions, options), options.wasm ?? true);
  const yieldNow = eventLoopYield();
  let yieldedMs = 0;
  for (;;) {
    const sliceStart = performance.now();
    if (state.step(sliceStart + sliceMs)) break;
    onProgress?.(state.progress());
    const before = performance.now();
    await yieldNow();
    yieldedMs += performance.now() - before;
    signal?.throwIfAborted();
  }
  const result = state.finish();
  // Report the work, not the time other tasks ran while we were yielding.
  result.buildTimeMs = Math.max(0, result.buildTimeMs - yieldedMs);
  onProgress?.(1);
  return result;
}

function workerCount(value: number | undefined): number {
  if (value === undefined) return defaultBvhWorkerCount();
  if (!Number.isInteger(value) || value < 0) throw new RangeError(`buildBvh: workers must be a non-negative integer, got ${value}`);
  return value;
}

/**
 * The parallel path: null when no worker could be started here (no Worker, a refused blob: URL, a
 * worker that failed), so the caller falls back to the calling thread. Aborts propagate.
 */
async function tryWorkers(positions: Float32Array, options: BvhAsyncBuildOptions, workers: number): Promise<BvhBuildResult | null> {
  const params = resolveBuildParams(positions, options);
  const pool = await getBvhWorkerPool(workers);
  options.signal?.throwIfAborted();
  if (!pool) return null;
  try {
    const result = await buildOnWorkers(positions, params, pool, {
      sliceMs: options.sliceMs ?? 8, signal: options.signal, onProgress: options.onProgress, wasm: options.wasm ?? true,
    });
    options.onProgress?.(1);
    return result;
  } catch (error) {
    options.signal?.throwIfAborted();
    if (error instanceof Error && error.message.startsWith('bvh worker')) return null;
    throw error;
  }
}

/**
 * Builds the same tree as `buildBvh` without blocking the calling thread for more than about
 * `sliceMs` at a time. Meshes of at least `BVH_PARALLEL_MIN_TRIANGLES` triangles are built by
 * `options.workers` inline Workers (default: one per hardware thread) where Workers can be started
 * (see `buildBvhParallel`); otherwise, and with `workers: 0`, the build runs on this thread in
 * slices of about `sliceMs` (default 8 ms, half a 60 Hz frame) between yields to the event loop. The
 * longest single stretch there is one node split, a few tens of ms at the root of a 1M-triangle mesh.
 */
export async function buildBvhAsync(positions: Float32Array, options: BvhAsyncBuildOptions = {}): Promise<BvhBuildResult> {
  options.signal?.throwIfAborted();
  resolveBuildParams(positions, options);
  const n = positions.length / 9;
  const workers = options.workers === undefined ? (n >= BVH_PARALLEL_MIN_TRIANGLES ? defaultBvhWorkerCount() : 0) : workerCount(options.workers);
  if (n === 0) return emptySceneResult(performance.now());
  if (workers > 0) {
    const result = await tryWorkers(positions, options, workers);
    if (result) return result;
  }
  return buildTimeSliced(positions, options);
}

/**
 * Builds the same tree as `buildBvh`, bit for bit, on `options.workers` Worker threads (default:
 * `navigator.hardwareConcurrency`, at most 8) sharing the triangle data through SharedArrayBuffer
 * (Node; browsers when the page is cross-origin isolated). Without SharedArrayBuffer one worker
 * builds a copy (no speed-up, but off the calling thread); where Workers cannot run at all it falls
 * back to the time-sliced build on the calling thread. Workers are inline (no worker file to
 * bundle), pooled for later builds and, in Node, never keep the process alive; see
 * `terminateBvhWorkers`.
 */
export async function buildBvhParallel(positions: Float32Array, options: BvhAsyncBuildOptions = {}): Promise<BvhBuildResult> {
  options.signal?.throwIfAborted();
  resolveBuildParams(positions, options);
  const workers = workerCount(options.workers);
  if (positions.length === 0) return emptySceneResult(performance.now());
  if (workers > 0) {
    const result = await tryWorkers(positions, options, workers);
    if (result) return result;
  }
  return buildTimeSliced(positions, options);
}
