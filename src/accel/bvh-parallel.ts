/**
 * The parallel build: the same binned-SAH tree as `buildBvh`, bit for bit, built by a pool of
 * workers (bvh-worker-pool.ts) that share the slot buffers through SharedArrayBuffer.
 *
 * Scheme (task parallelism over nodes, the usual two phases of parallel top-down builders):
 * 1. the AABB prepass is cut into one chunk per worker;
 * 2. nodes larger than `n / (TASKS_PER_WORKER * workers)` are split one at a time, each split a job
 *    for whichever worker is idle (largest node first), so after the root every worker is busy;
 * 3. smaller nodes become subtree jobs, each built depth first into the worker's own node buffer
 *    (the same resumable kernel as the single-threaded build), largest first;
 * 4. this thread lays the pieces out exactly as the depth-first single-threaded build does (sibling
 *    pairs in the order it would allocate them), relocating child indices by each block's offset.
 * Every node's split depends only on its triangles and depth, never on which worker ran it or when,
 * so the result does not depend on scheduling.
 *
 * Without SharedArrayBuffer (a browser page that is not cross-origin isolated) one worker runs the
 * whole single-threaded build on a copy of the positions: no speed-up, but the page stays responsive.
 * This thread only schedules, assembles (in slices of at most `sliceMs`) and evaluates the SAH cost.
 */
import { computeSahCost } from './bvh-sah.ts';
import type { BvhBuildParams } from './bvh-kernels.ts';
import { BVH_NODE_BYTES, bvhKernels, eventLoopYield } from './bvh-serial.ts';
import { compiledBvhWasm, wasmSlotLayout } from './bvh-wasm.ts';
import type { BvhBuildResult } from './bvh-build-types.ts';
import type { BvhWorkerPool, BvhWorkerReply } from './bvh-worker-pool.ts';

/** Subtree jobs per worker the top splits aim for (more balances better, costs more round trips). */
const TASKS_PER_WORKER = 4;
/** Floats copied into shared memory between two looks at the clock. */
const COPY_CHUNK = 1 << 18;
/** Nodes at most this large are never split as single jobs (a round trip costs more than their split). */
const MIN_SPLIT_JOB = 32768;

interface TopNode {
  start: number;
  count: number;
  depth: number;
  /** AABB (6) and doubled-centroid bounds (6). */
  bounds: Float64Array;
  kind: 'pending' | 'leaf' | 'interior' | 'subtree';
  children?: [TopNode, TopNode];
  subtree?: { nodes: ArrayBuffer; nodeCount: number; leafCount: number; depthReached: number };
}

export interface ParallelRunOptions {
  sliceMs: number;
  /** Use the WebAssembly loops where available (default true). */
  wasm?: boolean;
  signal?: AbortSignal;
  onProgress?: (fraction: number) => void;
}

let nextBuildId = 1;

function checkReply(reply: BvhWorkerReply): BvhWorkerReply {
  if (reply.aborted) throw new Error('bvh worker: aborted');
  return reply;
}

const yieldToLoop = eventLoopYield();

/** Builds on the pool's workers; rejects on abort (with `signal.reason`) or when a worker fails. */
export async function buildOnWorkers(
  positions: Float32Array, params: BvhBuildParams, pool: BvhWorkerPool, run: ParallelRunOptions,
): Promise<BvhBuildResult> {
  const startTime = performance.now();
  run.signal?.throwIfAborted();
  if (!pool.sharedMemory) return buildOnOneWorker(positions, params, pool, run, startTime);

  const n = positions.length / 9;
  const workerCount = pool.size();
  const build = nextBuildId++;
  // Shared inputs: the positions (copied below, unless they already live in shared memory) and
  // both slot buffers.
  const copyPositions = !(positions.buffer instanceof SharedArrayBuffer);
  const sharedPositions = copyPositions ? new Float32Array(new SharedArrayBuffer(positions.byteLength)) : positions;
  // Slots in one shared WebAssembly memory (the SIMD loops) or, without it, in SharedArrayBuffers.
  const module = run.wasm === false ? null : compiledBvhWasm(true);
  const layout = module ? wasmSlotLayout(n, workerCount, params.binCount) : null;
  let memory: WebAssembly.Memory | undefined;
  try {
    if (layout) memory = new WebAssembly.Memory({ initial: layout.pages, maximum: layout.pages, shared: true });
  } catch {
    memory = undefined;
  }
  const ids = memory ? new Uint32Array(memory.buffer, layout!.ids, n) : new Uint32Array(new SharedArrayBuffer(n * 4));
  const slots = memory ? undefined : { boxes: new Float32Array(new SharedArrayBuffer(n * 32)), ids };
  const abort = new Int32Array(new SharedArrayBuffer(4));
  const onAbort = (): void => void Atomics.store(abort, 0, 1);
  run.signal?.addEventListener('abort', onAbort, { once: true });
  const aborted = (): void => run.signal?.throwIfAborted();

  const begin = memory
    ? { op: 'begin', build, positions: sharedPositions, memory, module, layout, abort, params }
    : { op: 'begin', build, positions: sharedPositions, slots, abort, params };
  try {
    // Awaited below; a failure before then must not count as an unhandled rejection meanwhile.
    const quiet = <T>(promise: Promise<T>): Promise<T> => (promise.catch(() => {}), promise);
    const begun = Array.from({ length: workerCount }, (_, w) => quiet(pool.request(w, { ...begin, scratch: w * (layout?.scratchBytes ?? 0) })));

    // 1. Prepass, one chunk per worker, each started as soon as its positions are in shared memory
    //    (copied in slices, yielding in between: 1M triangles are 36 MB). Min/max merge exactly, so
    //    the root bounds equal the serial ones.
    const k = bvhKernels();
    const rootBounds = new Float64Array(12);
    k.emptyBounds(rootBounds, 0);
    const chunk = Math.ceil(n / workerCount);
    const prepass: Array<Promise<BvhWorkerReply>> = [];
    let sliceStart = performance.now();
    for (let w = 0; w < workerCount; w++) {
      const from = Math.min(n, w * chunk), to = Math.min(n, (w + 1) * chunk);
      for (let i = from * 9; copyPositions && i < to * 9; i += COPY_CHUNK) {
        sharedPositions.set(positions.subarray(i, Math.min(to * 9, i + COPY_CHUNK)), i);
        if (performance.now() - sliceStart > run.sliceMs) {
          await yieldToLoop();
          aborted();
          sliceStart = performance.now();
        }
      }
      prepass.push(quiet(pool.request(w, { op: 'boxes', build, from, to })));
    }
    await Promise.all(begun);
    for (const part of await Promise.all(prepass)) k.mergeBounds(rootBounds, 0, part.bounds as Float64Array, 0);
    aborted();

    // 2 + 3. Top splits and subtree jobs, largest node first, on whichever worker is idle.
    const root: TopNode = { start: 0, count: n, depth: 0, bounds: rootBounds, kind: 'pending' };
    const splitAbove = Math.max(MIN_SPLIT_JOB, Math.ceil(n / (TASKS_PER_WORKER * workerCount)));
    await schedule(root, splitAbove, n, build, pool, params, run);
    aborted();

    // 4. Layout.
    const assembled = await assemble(root, rootBounds, run);
    aborted();
    const triangleOrder = ids.slice();
    const buildTimeMs = performance.now() - startTime;

    return {
      nodes: assembled.nodes,
      nodeCount: assembled.nodeCount,
      triangleOrder,
      depth: assembled.depth,
      leafCount: assembled.leafCount,
      sahCost: computeSahCost(assembled.nodes, { nodeCount: assembled.nodeCount }),
      buildTimeMs,
    };
  } catch (error) {
    run.signal?.throwIfAborted();
    throw error;
  } finally {
    Atomics.store(abort, 0, 1);
    run.signal?.removeEventListener('abort', onAbort);
    for (let w = 0; w < workerCount; w++) pool.request(w, { op: 'end', build }).catch(() => {});
  }
}

function schedule(
  root: TopNode, splitAbove: number, n: number, build: number, pool: BvhWorkerPool, params: BvhBuildParams, run: ParallelRunOptions,
): Promise<void> {
  const workerCount = pool.size();
  const pending: TopNode[] = [root];
  const idle = Array.from({ length: workerCount }, (_, w) => w);
  let running = 0;
  let placed = 0;
  let failed = false;
  return new Promise<void>((resolve, reject) => {
    const fail = (error: unknown): void => {
      if (failed) return;
      failed = true;
      reject(error instanceof Error ? error : new Error(String(error)));
    };
    const onAbort = (): void => fail(run.signal!.reason);
    run.signal?.addEventListener('abort', onAbort, { once: true });
    const done = (): void => {
      run.signal?.removeEventListener('abort', onAbort);
      resolve();
    };
    const pump = (): void => {
      if (failed) return;
      while (idle.length > 0 && pending.length > 0) {
        // Largest first: big subtrees start early, small ones fill the gaps at the end.
        let best = 0;
        for (let i = 1; i < pending.length; i++) if (pending[i]!.count > pending[best]!.count) best = i;
        const node = pending.splice(best, 1)[0]!;
        // Prefer the idle worker with the fewest requests of other builds queued.
        idle.sort((a, b) => pool.load(b) - pool.load(a));
        const w = idle.pop()!;
        running++;
        const job = { build, start: node.start, count: node.count, depth: node.depth, bounds: node.bounds };
        const finished = (): void => {
          running--;
          idle.push(w);
          run.onProgress?.(placed / n);
          pump();
          if (!failed && running === 0 && pending.length === 0) done();
        };
        if (node.count > splitAbove && node.depth < params.maxDepth) {
          pool.request(w, { op: 'split', ...job }).then((reply) => {
            const mid = checkReply(reply).mid as number;
            if (mid < 0) {
              node.kind = 'leaf';
              placed += node.count;
            } else {
              const out = reply.out as Float64Array;
              node.kind = 'interior';
              const left: TopNode = { start: node.start, count: mid - node.start, depth: node.depth + 1, bounds: out.slice(0, 12), kind: 'pending' };
              const right: TopNode = { start: mid, count: node.start + node.count - mid, depth: node.depth + 1, bounds: out.slice(12, 24), kind: 'pending' };
              node.children = [left, right];
              pending.push(left, right);
            }
            finished();
          }, fail);
        } else {
          pool.request(w, { op: 'subtree', ...job }).then((reply) => {
            checkReply(reply);
            node.kind = 'subtree';
            node.subtree = {
              nodes: reply.nodes as ArrayBuffer,
              nodeCount: reply.nodeCount as number,
              leafCount: reply.leafCount as number,
              depthReached: reply.depth as number,
            };
            placed += node.count;
            finished();
          }, fail);
        }
      }
    };
    pump();
  });
}

/**
 * Lays the top nodes and subtree blocks out in the order of the depth-first single-threaded build:
 * a node's children pair is allocated when the node is processed, then its left subtree's nodes,
 * then its right subtree's. A subtree block's local node 0 is its root (already allocated in its
 * parent's pair); its local node i >= 1 lands at `next + i - 1`.
 */
async function assemble(
  root: TopNode, rootBounds: Float64Array, run: ParallelRunOptions,
): Promise<{ nodes: ArrayBuffer; nodeCount: number; depth: number; leafCount: number }> {
  let nodeCount = 1;
  let leafCount = 0;
  let depth = 0;
  const count = (node: TopNode): void => {
    if (node.kind === 'interior') {
      nodeCount += 2;
      count(node.children![0]);
      count(node.children![1]);
    } else if (node.kind === 'subtree') {
      nodeCount += node.subtree!.nodeCount - 1;
      leafCount += node.subtree!.leafCount;
      depth = Math.max(depth, node.subtree!.depthReached);
    } else {
      leafCount++;
      depth = Math.max(depth, node.depth);
    }
  };
  count(root);

  const nodes = new ArrayBuffer(nodeCount * BVH_NODE_BYTES);
  const f = new Float32Array(nodes);
  const u = new Uint32Array(nodes);
  const writeBox = (index: number, b: Float64Array, at: number): void => {
    const o = index * 8;
    f[o] = b[at]!; f[o + 1] = b[at + 1]!; f[o + 2] = b[at + 2]!;
    f[o + 4] = b[at + 3]!; f[o + 5] = b[at + 4]!; f[o + 6] = b[at + 5]!;
  };
  writeBox(0, rootBounds, 0);
  let next = 1;
  let sliceStart = performance.now();
  // Explicit stack of [node, index]; right pushed below left, as in the serial build.
  const stack: Array<[TopNode, number]> = [[root, 0]];
  while (stack.length > 0) {
    const [node, index] = stack.pop()!;
    if (node.kind === 'interior') {
      const left = next;
      next += 2;
      u[index * 8 + 3] = left;
      u[index * 8 + 7] = 0;
      writeBox(left, node.children![0].bounds, 0);
      writeBox(left + 1, node.children![1].bounds, 0);
      stack.push([node.children![1], left + 1], [node.children![0], left]);
    } else if (node.kind === 'leaf') {
      u[index * 8 + 3] = node.start;
      u[index * 8 + 7] = node.count;
    } else {
      const block = node.subtree!;
      const src = new Uint32Array(block.nodes, 0, block.nodeCount * 8);
      const shift = next - 1;
      // The root record keeps the box its parent wrote; its link moves with the block.
      u[index * 8 + 3] = src[7] === 0 ? src[3]! + shift : src[3]!;
      u[index * 8 + 7] = src[7]!;
      // Children records: copy, then move interior links (leaf links are global slots already).
      u.set(src.subarray(8), next * 8);
      for (let o = next * 8, end = (next + block.nodeCount - 1) * 8; o < end; o += 8) {
        if (u[o + 7] === 0) u[o + 3] = u[o + 3]! + shift;
      }
      next += block.nodeCount - 1;
      if (performance.now() - sliceStart > run.sliceMs) {
        await yieldToLoop();
        run.signal?.throwIfAborted();
        sliceStart = performance.now();
      }
    }
  }
  if (next !== nodeCount) throw new Error(`buildBvhParallel: internal error, laid out ${next} of ${nodeCount} nodes`);
  return { nodes, nodeCount, depth, leafCount };
}

/** Without shared memory: the whole single-threaded build on one worker, on a copy of the positions. */
async function buildOnOneWorker(
  positions: Float32Array, params: BvhBuildParams, pool: BvhWorkerPool, run: ParallelRunOptions, startTime: number,
): Promise<BvhBuildResult> {
  const copy = positions.slice();
  const n = positions.length / 9;
  const module = run.wasm === false ? null : compiledBvhWasm(false);
  const layout = module ? wasmSlotLayout(n, 1, params.binCount) : null;
  const reply = await new Promise<BvhWorkerReply>((resolve, reject) => {
    const onAbort = (): void => reject(run.signal!.reason);
    run.signal?.addEventListener('abort', onAbort, { once: true });
    const wasm = module && layout ? { module, layout } : {};
    pool.request(0, { op: 'full', build: 0, positions: copy, params, ...wasm }, [copy.buffer]).then(resolve, reject)
      .finally(() => run.signal?.removeEventListener('abort', onAbort));
  });
  const nodes = reply.nodes as ArrayBuffer;
  const nodeCount = reply.nodeCount as number;
  run.onProgress?.(1);
  return {
    nodes,
    nodeCount,
    triangleOrder: reply.order as Uint32Array,
    depth: reply.depth as number,
    leafCount: reply.leafCount as number,
    sahCost: computeSahCost(nodes, { nodeCount }),
    buildTimeMs: performance.now() - startTime,
  };
}
