/**
 * The binned-SAH BVH build kernels (Wald, "On fast construction of SAH-based bounding volume
 * hierarchies", IEEE RT 2007), shared by the single-threaded, time-sliced and parallel builds.
 *
 * `createBvhKernels` is deliberately self-contained: it references nothing outside its own body but
 * globals (Math, typed arrays, performance), because the parallel build ships its source text
 * (`createBvhKernels.toString()`) into an inline Worker. Every build path therefore runs the very
 * same code, and a parallel build produces the same tree, bit for bit, as the single-threaded one.
 *
 * Data layout (all flat typed arrays, no per-triangle objects):
 * - per slot 8 float32, two 4-vectors (min x, y, z, 0) and (max x, y, z, 0), and a u32 triangle id
 *   in a separate array; the same layout as the WebAssembly SIMD loops (bvh-wasm.ts), which replace
 *   binning, partitioning and scanning where WebAssembly runs;
 * - centroids are doubled and rounded to float32 (Math.fround(min + max), as f32x4.add), so the JS
 *   and WebAssembly loops put every triangle in the same bin and build the same tree, bit for bit;
 * - a node owns a contiguous range of slots; its partition reorders them in place (Hoare's scheme,
 *   two cursors from both ends), so the ids array ends up as `triangleOrder`;
 * - nodes: 32-byte records (boundsMin vec3f, leftOrFirst u32, boundsMax vec3f, primitiveCount u32),
 *   children of an interior node in a sibling pair at leftOrFirst, leftOrFirst + 1; pairs allocated
 *   in depth-first order (left subtree first).
 */

/** Resolved build settings (see `BvhBuildOptions`). */
export interface BvhBuildParams {
  maxLeafSize: number;
  binCount: number;
  leafSizeCap: number;
  maxDepth: number;
}

/** The slots (see the layout above); views may cover a sub-range of the whole. */
export interface SlotBuffers {
  boxes: Float32Array;
  ids: Uint32Array;
}

/** The WebAssembly loops (bvh-wasm.ts) and this thread's scratch in their memory (`wasmSlotLayout`). */
export interface BvhWasmBackend {
  exports: {
    bin(...args: number[]): void;
    partition(...args: number[]): number;
    scan(p: number, end: number, out: number): void;
    sweep(...args: number[]): void;
  };
  /** The instance's memory buffer; every slot buffer handed to the loops is a view of it. */
  buffer: ArrayBufferLike;
  scratch: number;
}

/** One depth-first subtree build over slots [0, count) of the given views. */
export interface SubtreeTask extends SlotBuffers {
  count: number;
  /** Global slot of local slot 0 (leaves store global slots). */
  slotBase: number;
  /** Depth of the subtree root in the whole tree (the depth cap counts from the whole tree's root). */
  depth: number;
  /** AABB (6) and doubled-centroid bounds (6) of the subtree's triangles. */
  rootBounds: Float64Array;
  /** Node records; local node 0 is the subtree root, its children start at local node 1. */
  nodes: ArrayBuffer;
  params: BvhBuildParams;
  /** The WebAssembly loops, when the slot buffers live in their memory. */
  wasm?: BvhWasmBackend;
}

export interface SubtreeBuild {
  /** Works until done or until `performance.now() >= deadline`; true when the subtree is complete. */
  step(deadline: number): boolean;
  nodeCount(): number;
  leafCount(): number;
  /** Deepest leaf, as a global depth. */
  depthReached(): number;
  /** Triangles already placed in leaves. */
  placed(): number;
}

export type BvhKernels = ReturnType<typeof createBvhKernels>;

export function createBvhKernels() {
  const TRAVERSAL_COST = 1;
  const INTERSECTION_COST = 1;
  const LEAF = 0;
  const MEDIAN = 1;
  const SAH = 2;

  function halfArea(minX: number, minY: number, minZ: number, maxX: number, maxY: number, maxZ: number): number {
    const dx = maxX - minX;
    const dy = maxY - minY;
    const dz = maxZ - minZ;
    return dx * dy + dy * dz + dz * dx;
  }

  /** Resets `out` (12: AABB then doubled-centroid bounds) to empty. */
  function emptyBounds(out: Float64Array, at: number): void {
    out[at] = out[at + 1] = out[at + 2] = Infinity;
    out[at + 3] = out[at + 4] = out[at + 5] = -Infinity;
    out[at + 6] = out[at + 7] = out[at + 8] = Infinity;
    out[at + 9] = out[at + 10] = out[at + 11] = -Infinity;
  }

  /**
   * Merges bounds `from` (12 at `fromAt`) into `into` (12 at `intoAt`). Min/max are exact; merged in
   * slot order, even ties between -0 and +0 resolve as in one pass over all slots (first one stays).
   */
  function mergeBounds(into: Float64Array, intoAt: number, from: Float64Array, fromAt: number): void {
    for (let c = 0; c < 12; c++) {
      const v = from[fromAt + c]!;
      if ((c % 6 < 3) ? v < into[intoAt + c]! : v > into[intoAt + c]!) into[intoAt + c] = v;
    }
  }

  /**
   * Triangle AABBs of triangles [from, to) into slots [from, to) of `boxes`/`ids`, and the union of
   * their AABBs and doubled centroids into `out` (12 at `at`, merged with what is there).
   */
  function computeBoxes(positions: Float32Array, boxes: Float32Array, ids: Uint32Array, from: number, to: number, out: Float64Array, at: number): void {
    let a0 = out[at]!, a1 = out[at + 1]!, a2 = out[at + 2]!, a3 = out[at + 3]!, a4 = out[at + 4]!, a5 = out[at + 5]!;
    let c0 = out[at + 6]!, c1 = out[at + 7]!, c2 = out[at + 8]!, c3 = out[at + 9]!, c4 = out[at + 10]!, c5 = out[at + 11]!;
    for (let t = from; t < to; t++) {
      const p = t * 9;
      const s = t * 8;
      const ax = positions[p]!, ay = positions[p + 1]!, az = positions[p + 2]!;
      const bx = positions[p + 3]!, by = positions[p + 4]!, bz = positions[p + 5]!;
      const cx = positions[p + 6]!, cy = positions[p + 7]!, cz = positions[p + 8]!;
      const x0 = ax < bx ? (ax < cx ? ax : cx) : bx < cx ? bx : cx;
      const y0 = ay < by ? (ay < cy ? ay : cy) : by < cy ? by : cy;
      const z0 = az < bz ? (az < cz ? az : cz) : bz < cz ? bz : cz;
      const x1 = ax > bx ? (ax > cx ? ax : cx) : bx > cx ? bx : cx;
      const y1 = ay > by ? (ay > cy ? ay : cy) : by > cy ? by : cy;
      const z1 = az > bz ? (az > cz ? az : cz) : bz > cz ? bz : cz;
      boxes[s] = x0;
      boxes[s + 1] = y0;
      boxes[s + 2] = z0;
      boxes[s + 3] = 0;
      boxes[s + 4] = x1;
      boxes[s + 5] = y1;
      boxes[s + 6] = z1;
      boxes[s + 7] = 0;
      ids[t] = t;
      if (x0 < a0) a0 = x0;
      if (y0 < a1) a1 = y0;
      if (z0 < a2) a2 = z0;
      if (x1 > a3) a3 = x1;
      if (y1 > a4) a4 = y1;
      if (z1 > a5) a5 = z1;
      const mx = Math.fround(x0 + x1), my = Math.fround(y0 + y1), mz = Math.fround(z0 + z1);
      if (mx < c0) c0 = mx;
      if (my < c1) c1 = my;
      if (mz < c2) c2 = mz;
      if (mx > c3) c3 = mx;
      if (my > c4) c4 = my;
      if (mz > c5) c5 = mz;
    }
    out[at] = a0; out[at + 1] = a1; out[at + 2] = a2; out[at + 3] = a3; out[at + 4] = a4; out[at + 5] = a5;
    out[at + 6] = c0; out[at + 7] = c1; out[at + 8] = c2; out[at + 9] = c3; out[at + 10] = c4; out[at + 11] = c5;
  }

  /** AABB and doubled-centroid bounds of slots [start, end) into `out` (12 at `at`), overwriting. */
  function scanBounds(boxes: Float32Array, start: number, end: number, out: Float64Array, at: number): void {
    let a0 = Infinity, a1 = Infinity, a2 = Infinity, a3 = -Infinity, a4 = -Infinity, a5 = -Infinity;
    let c0 = Infinity, c1 = Infinity, c2 = Infinity, c3 = -Infinity, c4 = -Infinity, c5 = -Infinity;
    for (let s = start * 8, e = end * 8; s < e; s += 8) {
      const x0 = boxes[s]!, y0 = boxes[s + 1]!, z0 = boxes[s + 2]!, x1 = boxes[s + 4]!, y1 = boxes[s + 5]!, z1 = boxes[s + 6]!;
      if (x0 < a0) a0 = x0;
      if (y0 < a1) a1 = y0;
      if (z0 < a2) a2 = z0;
      if (x1 > a3) a3 = x1;
      if (y1 > a4) a4 = y1;
      if (z1 > a5) a5 = z1;
      const mx = Math.fround(x0 + x1), my = Math.fround(y0 + y1), mz = Math.fround(z0 + z1);
      if (mx < c0) c0 = mx;
      if (my < c1) c1 = my;
      if (mz < c2) c2 = mz;
      if (mx > c3) c3 = mx;
      if (my > c4) c4 = my;
      if (mz > c5) c5 = mz;
    }
    out[at] = a0; out[at + 1] = a1; out[at + 2] = a2; out[at + 3] = a3; out[at + 4] = a4; out[at + 5] = a5;
    out[at + 6] = c0; out[at + 7] = c1; out[at + 8] = c2; out[at + 9] = c3; out[at + 10] = c4; out[at + 11] = c5;
  }

  /**
   * Bin scales of a node (into `scale`: k0, k1, k2, m0, m1, m2): bin(c) = floor(k * (c - m)) over the
   * doubled-centroid bounds `cb` (6 at `at`); k = 0 marks an axis on which all centroids coincide.
   */
  function binScales(cb: Float64Array, at: number, bins: number, scale: Float64Array): void {
    for (let a = 0; a < 3; a++) {
      const lo = cb[at + a]!, hi = cb[at + 3 + a]!;
      scale[a] = hi > lo ? (bins * (1 - 1e-9)) / (hi - lo) : 0;
      scale[3 + a] = lo;
    }
  }

  /** Empties `bins` bins per axis (bin records of 8 float32: min vector, max vector; `binStride` per axis). */
  function resetBins(binN: Int32Array, binB: Float32Array, bins: number, binStride: number): void {
    for (let a = 0; a < 3; a++) {
      for (let b = 0; b < bins; b++) {
        const q = a * binStride + b;
        binN[q] = 0;
        const r = q * 8;
        binB[r] = Infinity; binB[r + 1] = Infinity; binB[r + 2] = Infinity;
        binB[r + 4] = -Infinity; binB[r + 5] = -Infinity; binB[r + 6] = -Infinity;
      }
    }
  }

  /**
   * Adds slots [start, end) to the bins on all three axes in one pass (Wald 2007,
   * sec. 3.2: centroid binning, each bin keeping a count and the AABB of its triangles).
   */
  function binRange(boxes: Float32Array, start: number, end: number, scale: Float64Array, bins: number, binStride: number, binN: Int32Array, binB: Float32Array): void {
    const k0 = scale[0]!, k1 = scale[1]!, k2 = scale[2]!, m0 = scale[3]!, m1 = scale[4]!, m2 = scale[5]!;
    const last = bins - 1;
    const base1 = binStride, base2 = 2 * binStride;
    for (let s = start * 8, e = end * 8; s < e; s += 8) {
      const x0 = boxes[s]!, y0 = boxes[s + 1]!, z0 = boxes[s + 2]!, x1 = boxes[s + 4]!, y1 = boxes[s + 5]!, z1 = boxes[s + 6]!;
      if (k0 !== 0) {
        const f = k0 * (Math.fround(x0 + x1) - m0);
        const q = f >= last ? last : f > 0 ? f | 0 : 0;
        binN[q]!++;
        const r = q * 8;
        if (x0 < binB[r]!) binB[r] = x0;
        if (y0 < binB[r + 1]!) binB[r + 1] = y0;
        if (z0 < binB[r + 2]!) binB[r + 2] = z0;
        if (x1 > binB[r + 4]!) binB[r + 4] = x1;
        if (y1 > binB[r + 5]!) binB[r + 5] = y1;
        if (z1 > binB[r + 6]!) binB[r + 6] = z1;
      }
      if (k1 !== 0) {
        const f = k1 * (Math.fround(y0 + y1) - m1);
        const q = base1 + (f >= last ? last : f > 0 ? f | 0 : 0);
        binN[q]!++;
        const r = q * 8;
        if (x0 < binB[r]!) binB[r] = x0;
        if (y0 < binB[r + 1]!) binB[r + 1] = y0;
        if (z0 < binB[r + 2]!) binB[r + 2] = z0;
        if (x1 > binB[r + 4]!) binB[r + 4] = x1;
        if (y1 > binB[r + 5]!) binB[r + 5] = y1;
        if (z1 > binB[r + 6]!) binB[r + 6] = z1;
      }
      if (k2 !== 0) {
        const f = k2 * (Math.fround(z0 + z1) - m2);
        const q = base2 + (f >= last ? last : f > 0 ? f | 0 : 0);
        binN[q]!++;
        const r = q * 8;
        if (x0 < binB[r]!) binB[r] = x0;
        if (y0 < binB[r + 1]!) binB[r + 1] = y0;
        if (z0 < binB[r + 2]!) binB[r + 2] = z0;
        if (x1 > binB[r + 4]!) binB[r + 4] = x1;
        if (y1 > binB[r + 5]!) binB[r + 5] = y1;
        if (z1 > binB[r + 6]!) binB[r + 6] = z1;
      }
    }
  }

  /**
   * The SAH plane search over the bins of the axes with a non-zero scale (Wald 2007, sec. 3.3):
   * into `result` [best cost (times the parent's half area), axis (-1: none), plane, left count,
   * binned count]. The WebAssembly `sweep` computes the same, in the same order.
   */
  function sweepBins(
    binN: Int32Array, binB: Float32Array, bins: number, binStride: number, scale: Float64Array, parentArea: number,
    rightArea: Float64Array, rightN: Int32Array, result: Float64Array,
  ): void {
    let bestCost = Infinity;
    let bestAxis = -1;
    let bestPlane = 0;
    let bestLeftN = 0;
    let binned = 0;
    // Sweep the bins-1 planes of each axis: suffix areas right to left, then prefix left to right.
    for (let a = 0; a < 3; a++) {
      if (scale[a] === 0) continue;
      const base = a * binStride;
      let r0 = Infinity, r1 = Infinity, r2 = Infinity, r3 = -Infinity, r4 = -Infinity, r5 = -Infinity;
      let rn = 0;
      for (let b = bins - 1; b >= 1; b--) {
        const n = binN[base + b]!;
        if (n > 0) {
          const q = (base + b) * 8;
          rn += n;
          if (binB[q]! < r0) r0 = binB[q]!;
          if (binB[q + 1]! < r1) r1 = binB[q + 1]!;
          if (binB[q + 2]! < r2) r2 = binB[q + 2]!;
          if (binB[q + 4]! > r3) r3 = binB[q + 4]!;
          if (binB[q + 5]! > r4) r4 = binB[q + 5]!;
          if (binB[q + 6]! > r5) r5 = binB[q + 6]!;
        }
        rightN[b] = rn;
        rightArea[b] = rn > 0 ? halfArea(r0, r1, r2, r3, r4, r5) : 0;
      }
      binned = rn + binN[base]!;
      let l0 = Infinity, l1 = Infinity, l2 = Infinity, l3 = -Infinity, l4 = -Infinity, l5 = -Infinity;
      let ln = 0;
      for (let b = 0; b < bins - 1; b++) {
        const n = binN[base + b]!;
        if (n > 0) {
          const q = (base + b) * 8;
          ln += n;
          if (binB[q]! < l0) l0 = binB[q]!;
          if (binB[q + 1]! < l1) l1 = binB[q + 1]!;
          if (binB[q + 2]! < l2) l2 = binB[q + 2]!;
          if (binB[q + 4]! > l3) l3 = binB[q + 4]!;
          if (binB[q + 5]! > l4) l4 = binB[q + 5]!;
          if (binB[q + 6]! > l5) l5 = binB[q + 6]!;
        }
        const rnb = rightN[b + 1]!;
        if (ln === 0 || rnb === 0) continue;
        // Costs are kept multiplied by the parent's area (no division, so zero-area nodes made of
        // degenerate triangles compare without NaN): split = C_t A_P + C_i (A_L N_L + A_R N_R).
        const cost = TRAVERSAL_COST * parentArea + INTERSECTION_COST * (halfArea(l0, l1, l2, l3, l4, l5) * ln + rightArea[b + 1]! * rnb);
        if (cost < bestCost) {
          bestCost = cost;
          bestAxis = a;
          bestPlane = b + 1;
          bestLeftN = ln;
        }
      }
    }
    result[0] = bestCost;
    result[1] = bestAxis;
    result[2] = bestPlane;
    result[3] = bestLeftN;
    result[4] = binned;
  }

  /**
   * Chooses what to do with a swept node of `count` triangles:
   * returns LEAF, MEDIAN or SAH; for SAH `choice` gets [axis, plane, left count in the bins].
   */
  function decideSplit(result: Float64Array, parentArea: number, count: number, params: BvhBuildParams, choice: Int32Array): number {
    const bestCost = result[0]!, bestAxis = result[1]!, binned = result[4]!;
    const mustSplit = count > params.leafSizeCap;
    // No plane separates the centroids (all coincide, or one bin holds them all).
    if (bestAxis < 0) return mustSplit ? MEDIAN : LEAF;
    // A leaf (C_i N A_P, N as binned) is cheaper than any split: Wald 2007's termination criterion.
    if (bestCost >= INTERSECTION_COST * binned * parentArea && !mustSplit) return LEAF;
    choice[0] = bestAxis;
    choice[1] = result[2]!;
    choice[2] = result[3]!;
    return SAH;
  }

  /**
   * Depth budget: below a node at `depth` there are maxDepth - depth - 1 levels for its larger child;
   * with median splits from there on, a child of N triangles reaches leaves of <= leafSizeCap only if
   * N <= leafSizeCap * 2^levels. A very lopsided SAH split that breaks this is replaced by a median
   * split, which keeps every leaf bounded however adversarial the input is.
   */
  function withinDepthBudget(count: number, leftCount: number, depth: number, params: BvhBuildParams): boolean {
    const larger = leftCount > count - leftCount ? leftCount : count - leftCount;
    return larger <= params.leafSizeCap * 2 ** (params.maxDepth - depth - 1);
  }

  /**
   * In-place partition of slots [start, end) by bin(centroid on `axis`) < `plane` (Hoare's scheme:
   * a cursor from each end, swapping a right slot found from the left with a left slot found from
   * the right). Both sides' AABBs and doubled-centroid bounds go to `out` (left box, left cb, right
   * box, right cb); returns the first right slot. The WebAssembly `partition` visits and folds the
   * slots in the same order.
   */
  function partitionInPlace(
    boxes: Float32Array, ids: Uint32Array, start: number, end: number, axis: number, scale: Float64Array, bins: number, plane: number, out: Float64Array,
  ): number {
    const k = scale[axis]!, m = scale[3 + axis]!;
    const last = bins - 1;
    // Left box, left centroid bounds, right box, right centroid bounds: min xyz then max xyz each.
    const acc = out;
    for (let c = 0; c < 24; c += 6) {
      acc[c] = acc[c + 1] = acc[c + 2] = Infinity;
      acc[c + 3] = acc[c + 4] = acc[c + 5] = -Infinity;
    }
    const side = (slot: number): boolean => {
      const s = slot * 8;
      const f = k * (Math.fround(boxes[s + axis]! + boxes[s + 4 + axis]!) - m);
      const b = f >= last ? last : f > 0 ? f | 0 : 0;
      return b < plane;
    };
    const fold = (slot: number, at: number): void => {
      const s = slot * 8;
      const x0 = boxes[s]!, y0 = boxes[s + 1]!, z0 = boxes[s + 2]!, x1 = boxes[s + 4]!, y1 = boxes[s + 5]!, z1 = boxes[s + 6]!;
      if (x0 < acc[at]!) acc[at] = x0;
      if (y0 < acc[at + 1]!) acc[at + 1] = y0;
      if (z0 < acc[at + 2]!) acc[at + 2] = z0;
      if (x1 > acc[at + 3]!) acc[at + 3] = x1;
      if (y1 > acc[at + 4]!) acc[at + 4] = y1;
      if (z1 > acc[at + 5]!) acc[at + 5] = z1;
      const cx = Math.fround(x0 + x1), cy = Math.fround(y0 + y1), cz = Math.fround(z0 + z1);
      if (cx < acc[at + 6]!) acc[at + 6] = cx;
      if (cy < acc[at + 7]!) acc[at + 7] = cy;
      if (cz < acc[at + 8]!) acc[at + 8] = cz;
      if (cx > acc[at + 9]!) acc[at + 9] = cx;
      if (cy > acc[at + 10]!) acc[at + 10] = cy;
      if (cz > acc[at + 11]!) acc[at + 11] = cz;
    };
    let i = start;
    let j = end - 1;
    for (;;) {
      while (i <= j && side(i)) fold(i++, 0);
      while (i <= j && !side(j)) fold(j--, 12);
      if (i >= j) break;
      // Slot i belongs right, slot j left: swap them, then fold each into its side.
      const t = ids[i]!;
      ids[i] = ids[j]!;
      ids[j] = t;
      for (let c = 0; c < 8; c++) {
        const v = boxes[i * 8 + c]!;
        boxes[i * 8 + c] = boxes[j * 8 + c]!;
        boxes[j * 8 + c] = v;
      }
      fold(i++, 0);
      fold(j--, 12);
    }
    return i;
  }

  /**
   * Object-median split along the widest centroid axis (index halves when all centroids coincide):
   * Hoare quickselect, in place.
   */
  function medianSplit(boxes: Float32Array, ids: Uint32Array, start: number, count: number, cb: Float64Array, cbAt: number): number {
    const end = start + count;
    const mid = start + (count >>> 1);
    const ex = cb[cbAt + 3]! - cb[cbAt]!, ey = cb[cbAt + 4]! - cb[cbAt + 1]!, ez = cb[cbAt + 5]! - cb[cbAt + 2]!;
    if (ex > 0 || ey > 0 || ez > 0) {
      const axis = ex >= ey && ex >= ez ? 0 : ey >= ez ? 1 : 2;
      const key = (slot: number): number => Math.fround(boxes[slot * 8 + axis]! + boxes[slot * 8 + 4 + axis]!);
      const swap = (i: number, j: number): void => {
        const t = ids[i]!;
        ids[i] = ids[j]!;
        ids[j] = t;
        for (let c = 0; c < 8; c++) {
          const v = boxes[i * 8 + c]!;
          boxes[i * 8 + c] = boxes[j * 8 + c]!;
          boxes[j * 8 + c] = v;
        }
      };
      let lo = start;
      let hi = end - 1;
      while (hi > lo) {
        // Median of three as the pivot keeps sorted inputs (grids) from going quadratic.
        const m = (lo + hi) >>> 1;
        const a = key(lo), b = key(m), c = key(hi);
        const pivot = a < b ? (b < c ? b : a < c ? c : a) : a < c ? a : b < c ? c : b;
        let i = lo;
        let j = hi;
        while (i <= j) {
          while (key(i) < pivot) i++;
          while (key(j) > pivot) j--;
          if (i <= j) {
            swap(i, j);
            i++;
            j--;
          }
        }
        if (mid <= j) hi = j;
        else if (mid >= i) lo = i;
        else break;
      }
    }
    return mid;
  }

  /**
   * The per-node step shared by every build path: decides a node's split and partitions its slots
   * into the next buffer. `split` returns the first slot of the right child (children's AABBs and
   * doubled-centroid bounds in `out`: left box, left cb, right box, right cb), or -1 for a leaf.
   * With `wasm`, binning, partitioning and scans run in WebAssembly (same results).
   */
  function createSplitter(params: BvhBuildParams, wasm?: BvhWasmBackend) {
    const { maxLeafSize, binCount, maxDepth, leafSizeCap } = params;
    const binStride = binCount;
    // In WebAssembly memory everything below sits in this thread's scratch (see wasmSlotLayout): bin
    // records, counts, 8 result vectors, the sweep's result and suffix arrays, the f64 parameters.
    const binBytes = 3 * binStride * 32;
    const cntBytes = 3 * binStride * 4;
    if (wasm && wasm.scratch % 16 !== 0) throw new RangeError('bvh: WebAssembly scratch must be 16-byte aligned');
    const binB = wasm ? new Float32Array(wasm.buffer, wasm.scratch, 3 * binStride * 8) : new Float32Array(3 * binStride * 8);
    const binN = wasm ? new Int32Array(wasm.buffer, wasm.scratch + binBytes, 3 * binStride) : new Int32Array(3 * binStride);
    const results = wasm ? new Float32Array(wasm.buffer, wasm.scratch + binBytes + cntBytes, 32) : new Float32Array(32);
    const resultsAt = wasm ? wasm.scratch + binBytes + cntBytes : 0;
    // The WebAssembly sweep's result (f64 cost, then i32 axis, plane, left count, binned) and its suffix arrays.
    const sweepAt = resultsAt + 128;
    const sweepCost = wasm ? new Float64Array(wasm.buffer, sweepAt, 1) : new Float64Array(1);
    const sweepInts = wasm ? new Int32Array(wasm.buffer, sweepAt + 8, 4) : new Int32Array(4);
    const sweepTmp = sweepAt + 32;
    const swept = new Float64Array(5);
    // f64 parameters of the WebAssembly calls (k0, k1, k2, m0, m1, m2, last bin, parent area).
    const paramsAt = sweepTmp + binStride * 12;
    const wasmParams = wasm ? new Float64Array(wasm.buffer, paramsAt, 8) : new Float64Array(8);
    const rightArea = new Float64Array(binStride);
    const rightN = new Int32Array(binStride);
    const scale = new Float64Array(6);
    const choice = new Int32Array(3);

    /** Vectors (min, max) at results[4v..] into out[at..at+6). */
    const readVectors = (v: number, out: Float64Array, at: number): void => {
      out[at] = results[v * 4]!; out[at + 1] = results[v * 4 + 1]!; out[at + 2] = results[v * 4 + 2]!;
      out[at + 3] = results[v * 4 + 4]!; out[at + 4] = results[v * 4 + 5]!; out[at + 5] = results[v * 4 + 6]!;
    };
    const scan = (boxes: Float32Array, start: number, end: number, out: Float64Array, at: number): void => {
      if (!wasm) return scanBounds(boxes, start, end, out, at);
      wasm.exports.scan(boxes.byteOffset + start * 32, boxes.byteOffset + end * 32, resultsAt);
      readVectors(0, out, at);
      readVectors(2, out, at + 6);
    };

    function split(
      slots: SlotBuffers, start: number, count: number, depth: number,
      box: Float64Array, boxAt: number, cb: Float64Array, cbAt: number, out: Float64Array,
    ): number {
      if (count <= maxLeafSize || depth >= maxDepth) return -1;
      const { boxes, ids } = slots;
      // Fewer bins than triangles cannot help; small nodes sweep fewer planes.
      const bins = count < binCount ? count : binCount;
      binScales(cb, cbAt, bins, scale);
      let decision = count > leafSizeCap ? MEDIAN : LEAF;
      if (scale[0] !== 0 || scale[1] !== 0 || scale[2] !== 0) {
        const parentArea = halfArea(box[boxAt]!, box[boxAt + 1]!, box[boxAt + 2]!, box[boxAt + 3]!, box[boxAt + 4]!, box[boxAt + 5]!);
        if (wasm) {
          const p = boxes.byteOffset + start * 32;
          for (let c = 0; c < 6; c++) wasmParams[c] = scale[c]!;
          wasmParams[6] = bins - 1;
          wasmParams[7] = parentArea;
          wasm.exports.bin(p, p + count * 32, bins - 1, binB.byteOffset, binN.byteOffset, binStride, paramsAt);
          const mask = (scale[0] !== 0 ? 1 : 0) | (scale[1] !== 0 ? 2 : 0) | (scale[2] !== 0 ? 4 : 0);
          wasm.exports.sweep(binB.byteOffset, binN.byteOffset, bins, binStride, mask, sweepTmp, sweepAt, paramsAt);
          swept[0] = sweepCost[0]!;
          swept[1] = sweepInts[0]!;
          swept[2] = sweepInts[1]!;
          swept[3] = sweepInts[2]!;
          swept[4] = sweepInts[3]!;
        } else {
          resetBins(binN, binB, bins, binStride);
          binRange(boxes, start, start + count, scale, bins, binStride, binN, binB);
          sweepBins(binN, binB, bins, binStride, scale, parentArea, rightArea, rightN, swept);
        }
        decision = decideSplit(swept, parentArea, count, params, choice);
      }
      if (decision === SAH && !withinDepthBudget(count, choice[2]!, depth, params)) decision = MEDIAN;
      if (decision === LEAF) return -1;
      if (decision === SAH) {
        const axis = choice[0]!, plane = choice[1]!;
        let mid: number;
        if (wasm) {
          const left = wasm.exports.partition(
            boxes.byteOffset + start * 32, boxes.byteOffset + (start + count - 1) * 32,
            ids.byteOffset + start * 4, ids.byteOffset + (start + count - 1) * 4,
            axis * 4, bins - 1, plane, resultsAt, paramsAt,
          );
          mid = start + left;
          readVectors(0, out, 0);
          readVectors(2, out, 6);
          readVectors(4, out, 12);
          readVectors(6, out, 18);
        } else {
          mid = partitionInPlace(boxes, ids, start, start + count, axis, scale, bins, plane, out);
        }
        if (mid - start !== choice[2]) throw new Error(`bvh: internal error, partition ${mid - start} != binned ${choice[2]}`);
        return mid;
      }
      const mid = medianSplit(boxes, ids, start, count, cb, cbAt);
      scan(boxes, start, mid, out, 0);
      scan(boxes, mid, start + count, out, 12);
      return mid;
    }
    return split;
  }

  /**
   * Resumable depth-first build of one subtree (the whole tree for the single-threaded build). The
   * work stack is explicit: each level pushes two entries and pops one, so maxDepth + 2 pairs suffice.
   */
  function createSubtreeBuild(task: SubtreeTask): SubtreeBuild {
    const { count: total, slotBase, params } = task;
    const split = createSplitter(params, task.wasm);
    const nodeF = new Float32Array(task.nodes);
    const nodeU = new Uint32Array(task.nodes);
    const stackCap = 2 * (params.maxDepth + 2);
    const stNode = new Int32Array(stackCap);
    const stStart = new Int32Array(stackCap);
    const stCount = new Int32Array(stackCap);
    const stDepth = new Int32Array(stackCap);
    const stCb = new Float64Array(stackCap * 6);
    const out = new Float64Array(24);
    const cb = new Float64Array(6);
    const box = new Float64Array(6);
    let nodeCount = 1;
    let leafCount = 0;
    let depthReached = task.depth;
    let placed = 0;
    let sp = 0;

    const writeBox = (node: number, b: Float64Array, at: number): void => {
      const o = node * 8;
      nodeF[o] = b[at]!;
      nodeF[o + 1] = b[at + 1]!;
      nodeF[o + 2] = b[at + 2]!;
      nodeF[o + 4] = b[at + 3]!;
      nodeF[o + 5] = b[at + 4]!;
      nodeF[o + 6] = b[at + 5]!;
    };
    const push = (node: number, start: number, count: number, depth: number, from: Float64Array, at: number): void => {
      stNode[sp] = node;
      stStart[sp] = start;
      stCount[sp] = count;
      stDepth[sp] = depth;
      for (let c = 0; c < 6; c++) stCb[sp * 6 + c] = from[at + c]!;
      sp++;
    };

    const processNode = (node: number, start: number, count: number, depth: number): void => {
      const o = node * 8;
      box[0] = nodeF[o]!; box[1] = nodeF[o + 1]!; box[2] = nodeF[o + 2]!;
      box[3] = nodeF[o + 4]!; box[4] = nodeF[o + 5]!; box[5] = nodeF[o + 6]!;
      const mid = split(task, start, count, depth, box, 0, cb, 0, out);
      if (mid < 0) {
        nodeU[node * 8 + 3] = slotBase + start;
        nodeU[node * 8 + 7] = count;
        leafCount++;
        placed += count;
        if (depth > depthReached) depthReached = depth;
        return;
      }
      const left = nodeCount;
      nodeCount += 2;
      nodeU[node * 8 + 3] = left;
      nodeU[node * 8 + 7] = 0;
      writeBox(left, out, 0);
      writeBox(left + 1, out, 12);
      // Right below left: the left subtree is finished first, so it is laid out first.
      push(left + 1, mid, start + count - mid, depth + 1, out, 18);
      push(left, start, mid - start, depth + 1, out, 6);
    };

    writeBox(0, task.rootBounds, 0);
    if (total > 0) push(0, 0, total, task.depth, task.rootBounds, 6);

    const step = (deadline: number): boolean => {
      const timed = deadline !== Infinity;
      let sinceCheck = 0;
      while (sp > 0) {
        sp--;
        const node = stNode[sp]!;
        const start = stStart[sp]!;
        const count = stCount[sp]!;
        const depth = stDepth[sp]!;
        for (let c = 0; c < 6; c++) cb[c] = stCb[sp * 6 + c]!;
        processNode(node, start, count, depth);
        // Reading the clock costs more than a small node; check every few nodes or after big ones.
        sinceCheck += count;
        if (timed && sinceCheck >= 4096) {
          sinceCheck = 0;
          if (performance.now() >= deadline) return sp === 0;
        }
      }
      return true;
    };

    return {
      step,
      nodeCount: () => nodeCount,
      leafCount: () => leafCount,
      depthReached: () => depthReached,
      placed: () => placed,
    };
  }

  return {
    LEAF, MEDIAN, SAH,
    emptyBounds, mergeBounds, computeBoxes, scanBounds, binScales, resetBins, binRange,
    sweepBins, decideSplit, withinDepthBudget, partitionInPlace, medianSplit, createSplitter, createSubtreeBuild,
  };
}
