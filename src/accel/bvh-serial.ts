/**
 * The single-threaded build (synchronous or time-sliced) on top of the shared kernels, plus what
 * every build path needs: settings validation and the result record.
 */
import { computeSahCost } from './bvh-sah.ts';
import { createBvhKernels, type BvhBuildParams, type BvhKernels, type BvhWasmBackend, type SlotBuffers } from './bvh-kernels.ts';
import { compiledBvhWasm, wasmSlotLayout } from './bvh-wasm.ts';
import type { BvhBuildOptions, BvhBuildResult } from './bvh-build-types.ts';

/** Hard depth limit: the WGSL traversal stack holds 64 entries and pushes at most one per level. */
export const BVH_MAX_DEPTH = 48;

/** Bytes of one packed node; mirrors `bvhNodeLayout` (boundsMin, leftOrFirst, boundsMax, primitiveCount). */
export const BVH_NODE_BYTES = 32;

/** Triangles per chunk of the AABB prepass (the time-sliced build may yield between chunks). */
const BOUNDS_CHUNK = 65536;

let sharedKernels: BvhKernels | undefined;

/** The kernels of this thread (created once). */
export function bvhKernels(): BvhKernels {
  sharedKernels ??= createBvhKernels();
  return sharedKernels;
}

/** A function that gives the event loop one turn. */
export function eventLoopYield(): () => Promise<void> {
  // `scheduler.yield()` (Prioritized Task Scheduling) resumes ahead of other queued tasks yet lets
  // input and rendering run; elsewhere a zero timeout gives the event loop one turn.
  const scheduler = (globalThis as { scheduler?: { yield?: () => Promise<void> } }).scheduler;
  if (scheduler && typeof scheduler.yield === 'function') return () => scheduler.yield!();
  return () => new Promise<void>((resolve) => setTimeout(resolve, 0));
}

function positiveInt(value: number | undefined, fallback: number, name: string): number {
  if (value === undefined) return fallback;
  if (!Number.isInteger(value) || value < 1) throw new RangeError(`buildBvh: ${name} must be a positive integer, got ${value}`);
  return value;
}

/** Validates the input and resolves the options' defaults; throws RangeError on bad input. */
export function resolveBuildParams(positions: Float32Array, options: BvhBuildOptions = {}): BvhBuildParams {
  if (positions.length % 9 !== 0) throw new RangeError(`buildBvh: positions length ${positions.length} is not a multiple of 9`);
  const maxLeafSize = positiveInt(options.maxLeafSize, 4, 'maxLeafSize');
  const binCount = Math.max(2, positiveInt(options.binCount, 16, 'binCount'));
  const leafSizeCap = Math.max(maxLeafSize, positiveInt(options.leafSizeCap, 16, 'leafSizeCap'));
  const maxDepth = Math.min(BVH_MAX_DEPTH, options.maxDepth ?? BVH_MAX_DEPTH);
  if (!Number.isInteger(maxDepth) || maxDepth < 0) throw new RangeError(`buildBvh: maxDepth must be a non-negative integer`);
  return { maxLeafSize, binCount, leafSizeCap, maxDepth };
}

/** The tree of an empty scene: one inverted root box that no slab test can enter. */
export function emptySceneResult(startTime: number): BvhBuildResult {
  const nodes = new ArrayBuffer(BVH_NODE_BYTES);
  const f = new Float32Array(nodes);
  f[0] = f[1] = f[2] = 3.4e38;
  f[4] = f[5] = f[6] = -3.4e38;
  // A 0-count "interior" root that traversal never reads, since it checks triangleCount first.
  return {
    nodes,
    nodeCount: 1,
    triangleOrder: new Uint32Array(0),
    depth: 0,
    leafCount: 0,
    sahCost: computeSahCost(nodes, { nodeCount: 1 }),
    buildTimeMs: performance.now() - startTime,
  };
}

export interface SerialBuildState {
  /** Runs until done or until `performance.now() >= deadline`; true when the tree is complete. */
  step(deadline: number): boolean;
  /** Fraction of triangles already placed in leaves. */
  progress(): number;
  finish(): BvhBuildResult;
}

/** Where the single-threaded build keeps its slots: WebAssembly memory when the SIMD loops run here. */
function allocateSlots(n: number, params: BvhBuildParams, useWasm: boolean): { slots: SlotBuffers; wasm?: BvhWasmBackend } {
  const module = useWasm ? compiledBvhWasm(false) : null;
  const layout = module ? wasmSlotLayout(n, 1, params.binCount) : null;
  if (module && layout) {
    try {
      const memory = new WebAssembly.Memory({ initial: layout.pages });
      const instance = new WebAssembly.Instance(module, { env: { memory } });
      const buffer = memory.buffer;
      return {
        slots: { boxes: new Float32Array(buffer, layout.boxes, n * 8), ids: new Uint32Array(buffer, layout.ids, n) },
        wasm: { exports: instance.exports as unknown as BvhWasmBackend['exports'], buffer, scratch: 0 },
      };
    } catch {
      // Out of memory for one contiguous block, or an engine without SIMD: the JS loops do the same.
    }
  }
  return { slots: { boxes: new Float32Array(n * 8), ids: new Uint32Array(n) } };
}

/**
 * A resumable single-threaded build: the AABB prepass in chunks, then one depth-first subtree build.
 * `useWasm: false` keeps every loop in JS (the same tree; for tests and engines without WebAssembly).
 */
export function createSerialBuildState(positions: Float32Array, params: BvhBuildParams, useWasm = true): SerialBuildState {
  const startTime = performance.now();
  const n = positions.length / 9;
  const k = bvhKernels();
  const { slots, wasm } = allocateSlots(n, params, useWasm && n > 0);
  const rootBounds = new Float64Array(12);
  k.emptyBounds(rootBounds, 0);
  // A binary tree whose leaves hold >= 1 triangle has at most 2n - 1 nodes.
  const nodes = new ArrayBuffer(Math.max(1, 2 * n - 1) * BVH_NODE_BYTES);
  let boundsDone = 0;
  let build: ReturnType<BvhKernels['createSubtreeBuild']> | undefined;
  let done = n === 0;

  const step = (deadline: number): boolean => {
    if (done) return true;
    while (boundsDone < n) {
      const end = Math.min(n, boundsDone + BOUNDS_CHUNK);
      k.computeBoxes(positions, slots.boxes, slots.ids, boundsDone, end, rootBounds, 0);
      boundsDone = end;
      if (performance.now() >= deadline && boundsDone < n) return false;
    }
    build ??= k.createSubtreeBuild({ ...slots, count: n, slotBase: 0, depth: 0, rootBounds, nodes, params, wasm });
    done = build.step(deadline);
    return done;
  };

  const finish = (): BvhBuildResult => {
    if (!done) throw new Error('buildBvh: finish() before the build completed');
    if (n === 0) return emptySceneResult(startTime);
    const nodeCount = build!.nodeCount();
    const exact = nodes.slice(0, nodeCount * BVH_NODE_BYTES);
    const buildTimeMs = performance.now() - startTime;
    return {
      nodes: exact,
      nodeCount,
      // Out of WebAssembly memory into a buffer of its own (the memory is dropped with the build).
      triangleOrder: wasm ? slots.ids.slice() : slots.ids,
      depth: build!.depthReached(),
      leafCount: build!.leafCount(),
      sahCost: computeSahCost(exact, { nodeCount }),
      buildTimeMs,
    };
  };

  return { step, progress: () => (n === 0 ? 1 : (build?.placed() ?? 0) / n), finish };
}
