// The options and result of a CPU BVH build, shared by the builder's entry points (bvh-builder.ts)
// and the serial and parallel builds beneath them.

export interface BvhBuildOptions {
  /** Nodes with at most this many triangles become leaves without evaluating splits (default 4). */
  maxLeafSize?: number;
  /** SAH bins per axis over the centroid bounds (default 16, Wald 2007 reports 16-32 suffice). */
  binCount?: number;
  /** Leaves larger than this are split even when the SAH says a leaf is cheaper (default 16). */
  leafSizeCap?: number;
  /** Depth limit (root = 0), at most and by default BVH_MAX_DEPTH. */
  maxDepth?: number;
  /**
   * Run the hot loops as WebAssembly SIMD where the engine allows it (default true). The tree is the
   * same either way, bit for bit; false keeps everything in JS, e.g. under a Content Security Policy
   * without 'wasm-unsafe-eval', where even the attempt to compile would be reported as a violation.
   */
  wasm?: boolean;
}

export interface BvhAsyncBuildOptions extends BvhBuildOptions {
  /** Longest stretch of work on the calling thread between two yields to the event loop, in ms (default 8). */
  sliceMs?: number;
  /** Aborts the build; the promise rejects with `signal.reason`. */
  signal?: AbortSignal;
  /** Called now and then with the fraction of triangles already placed in leaves (last call: 1). */
  onProgress?: (fraction: number) => void;
  /**
   * Worker threads for the parallel build: 0 keeps the build on the calling thread (time-sliced).
   * Default: `navigator.hardwareConcurrency` (at most 8) for meshes of at least
   * `BVH_PARALLEL_MIN_TRIANGLES` triangles, else 0. With `buildBvhParallel` the default applies to
   * any size.
   */
  workers?: number;
}

export interface BvhBuildResult {
  /** Packed `bvhNodeLayout` records, `nodeCount * 32` bytes. */
  nodes: ArrayBuffer;
  nodeCount: number;
  /** BVH slot -> original triangle index; leaves reference ranges of slots. */
  triangleOrder: Uint32Array;
  /** Edges from the root to the deepest leaf (a lone root leaf has depth 0). */
  depth: number;
  leafCount: number;
  /** SAH cost of the tree with C_trav = C_isect = 1 (see `computeSahCost`). */
  sahCost: number;
  /**
   * Wall time of the construction (bounds prepass, splits, output), without the SAH evaluation;
   * for the time-sliced build without the time other tasks ran while it yielded.
   */
  buildTimeMs: number;
}
