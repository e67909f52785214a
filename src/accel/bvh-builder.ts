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
 * Everything works on flat typed arrays (per-triangle AABBs in a Float32Array that is permuted in
 * place together with the Uint32Array of triangle ids) so a 1M-triangle build allocates a handful of
 * large arrays and no per-triangle objects.
 */
import { computeSahCost } from './bvh-sah.ts';

/** Hard depth limit: the WGSL traversal stack holds 64 entries and pushes at most one per level. */
export const BVH_MAX_DEPTH = 48;

/** Bytes of one packed node; mirrors `bvhNodeLayout` (boundsMin, leftOrFirst, boundsMax, primitiveCount). */
export const BVH_NODE_BYTES = 32;

export interface BvhBuildOptions {
  /** Nodes with at most this many triangles become leaves without evaluating splits (default 4). */
  maxLeafSize?: number;
  /** SAH bins per axis over the centroid bounds (default 16, Wald 2007 reports 16-32 suffice). */
  binCount?: number;
  /** Leaves larger than this are split even when the SAH says a leaf is cheaper (default 16). */
  leafSizeCap?: number;
  /** Depth limit (root = 0), at most and by default BVH_MAX_DEPTH. */
  maxDepth?: number;
}

export interface BvhAsyncBuildOptions extends BvhBuildOptions {
  /** Longest stretch of work between two yields to the event loop, in milliseconds (default 8). */
  sliceMs?: number;
  /** Aborts the build; the promise rejects with `signal.reason`. */
  signal?: AbortSignal;
  /** Called after each slice with the fraction of triangles already placed in leaves. */
  onProgress?: (fraction: number) => void;
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
  /** Wall time of the construction (bounds prepass, splits, output), without the SAH evaluation. */
  buildTimeMs: number;
}

const TRAVERSAL_COST = 1;
const INTERSECTION_COST = 1;
const BOUNDS_CHUNK = 65536;

interface BuildState {
  /** Runs until done or until `now() >= deadline`; returns true when the tree is complete. */
  step(deadline: number): boolean;
  /** Fraction of triangles already placed in leaves. */
  progress(): number;
  finish(): BvhBuildResult;
}

function positiveInt(value: number | undefined, fallback: number, name: string): number {
  if (value === undefined) return fallback;
  if (!Number.isInteger(value) || value < 1) throw new RangeError(`buildBvh: ${name} must be a positive integer, got ${value}`);
  return value;
}

function createBuildState(positions: Float32Array, options: BvhBuildOptions = {}): BuildState {
  if (positions.length % 9 !== 0) throw new RangeError(`buildBvh: positions length ${positions.length} is not a multiple of 9`);
  const startTime = performance.now();
  const n = positions.length / 9;
  const maxLeafSize = positiveInt(options.maxLeafSize, 4, 'maxLeafSize');
  const binCount = Math.max(2, positiveInt(options.binCount, 16, 'binCount'));
  const leafSizeCap = Math.max(maxLeafSize, positiveInt(options.leafSizeCap, 16, 'leafSizeCap'));
  const maxDepth = Math.min(BVH_MAX_DEPTH, options.maxDepth ?? BVH_MAX_DEPTH);
  if (!Number.isInteger(maxDepth) || maxDepth < 0) throw new RangeError(`buildBvh: maxDepth must be a non-negative integer`);

  // Per-slot triangle AABBs (min xyz, max xyz), permuted in place with `order` during partitioning,
  // so every pass over a node's range reads memory sequentially.
  const boxes = new Float32Array(n * 6);
  const order = new Uint32Array(n);
  // A binary tree whose leaves hold >= 1 triangle has at most 2n - 1 nodes.
  const capacity = Math.max(1, 2 * n - 1);
  const nodeBuffer = new ArrayBuffer(capacity * BVH_NODE_BYTES);
  const nodeF = new Float32Array(nodeBuffer);
  const nodeU = new Uint32Array(nodeBuffer);
  let nodeCount = 1;
  let leafCount = 0;
  let depthReached = 0;
  let placed = 0;
  let boundsDone = 0;
  let done = false;

  // Explicit work stack (depth first: right child pushed below the left). Each level pushes two and
  // pops one, so maxDepth + 2 entries suffice.
  const stackCap = 2 * (maxDepth + 2);
  const stNode = new Int32Array(stackCap);
  const stStart = new Int32Array(stackCap);
  const stCount = new Int32Array(stackCap);
  const stDepth = new Int32Array(stackCap);
  // Centroid bounds of the pending node, stored as doubled centroids (min + max) to save a multiply.
  const stCb = new Float64Array(stackCap * 6);
  let sp = 0;

  // Bin storage: for each axis, bin counts and bin AABBs.
  const binN = new Int32Array(3 * binCount);
  const binB = new Float64Array(3 * binCount * 6);
  // Suffix areas/counts of the right-hand sweep.
  const rightArea = new Float64Array(binCount);
  const rightN = new Int32Array(binCount);
  const tmpL = new Float64Array(6);
  const tmpR = new Float64Array(6);
  const cbL = new Float64Array(6);
  const cbR = new Float64Array(6);

  const halfArea = (minX: number, minY: number, minZ: number, maxX: number, maxY: number, maxZ: number): number => {
    const dx = maxX - minX;
    const dy = maxY - minY;
    const dz = maxZ - minZ;
    return dx * dy + dy * dz + dz * dx;
  };

  const writeBounds = (node: number, b: ArrayLike<number>): void => {
    const o = node * 8;
    nodeF[o] = b[0]!;
    nodeF[o + 1] = b[1]!;
    nodeF[o + 2] = b[2]!;
    nodeF[o + 4] = b[3]!;
    nodeF[o + 5] = b[4]!;
    nodeF[o + 6] = b[5]!;
  };

  /** Node AABB and doubled-centroid bounds of slots [start, start + count). */
  const scanBounds = (start: number, count: number, outBox: Float64Array, outCb: Float64Array): void => {
    let a0 = Infinity, a1 = Infinity, a2 = Infinity, a3 = -Infinity, a4 = -Infinity, a5 = -Infinity;
    let c0 = Infinity, c1 = Infinity, c2 = Infinity, c3 = -Infinity, c4 = -Infinity, c5 = -Infinity;
    for (let i = start * 6, end = (start + count) * 6; i < end; i += 6) {
      const x0 = boxes[i]!, y0 = boxes[i + 1]!, z0 = boxes[i + 2]!, x1 = boxes[i + 3]!, y1 = boxes[i + 4]!, z1 = boxes[i + 5]!;
      if (x0 < a0) a0 = x0;
      if (y0 < a1) a1 = y0;
      if (z0 < a2) a2 = z0;
      if (x1 > a3) a3 = x1;
      if (y1 > a4) a4 = y1;
      if (z1 > a5) a5 = z1;
      const cx = x0 + x1, cy = y0 + y1, cz = z0 + z1;
      if (cx < c0) c0 = cx;
      if (cy < c1) c1 = cy;
      if (cz < c2) c2 = cz;
      if (cx > c3) c3 = cx;
      if (cy > c4) c4 = cy;
      if (cz > c5) c5 = cz;
    }
    outBox[0] = a0; outBox[1] = a1; outBox[2] = a2; outBox[3] = a3; outBox[4] = a4; outBox[5] = a5;
    outCb[0] = c0; outCb[1] = c1; outCb[2] = c2; outCb[3] = c3; outCb[4] = c4; outCb[5] = c5;
  };

  const swapSlots = (i: number, j: number): void => {
    const t = order[i]!;
    order[i] = order[j]!;
    order[j] = t;
    const a = i * 6, b = j * 6;
    for (let k = 0; k < 6; k++) {
      const v = boxes[a + k]!;
      boxes[a + k] = boxes[b + k]!;
      boxes[b + k] = v;
    }
  };

  const key = (slot: number, axis: number): number => boxes[slot * 6 + axis]! + boxes[slot * 6 + 3 + axis]!;

  /** Hoare quickselect: afterwards slots [start, mid) have keys <= those of [mid, end). */
  const selectMedian = (start: number, end: number, mid: number, axis: number): void => {
    let lo = start;
    let hi = end - 1;
    while (hi > lo) {
      // Median of three as the pivot keeps sorted inputs (grids) from going quadratic.
      const m = (lo + hi) >>> 1;
      const a = key(lo, axis), b = key(m, axis), c = key(hi, axis);
      const pivot = a < b ? (b < c ? b : a < c ? c : a) : a < c ? a : b < c ? c : b;
      let i = lo;
      let j = hi;
      while (i <= j) {
        while (key(i, axis) < pivot) i++;
        while (key(j, axis) > pivot) j--;
        if (i <= j) {
          swapSlots(i, j);
          i++;
          j--;
        }
      }
      if (mid <= j) hi = j;
      else if (mid >= i) lo = i;
      else return;
    }
  };

  const push = (node: number, start: number, count: number, depth: number, cb: ArrayLike<number>): void => {
    stNode[sp] = node;
    stStart[sp] = start;
    stCount[sp] = count;
    stDepth[sp] = depth;
    for (let k = 0; k < 6; k++) stCb[sp * 6 + k] = cb[k]!;
    sp++;
  };

  const makeLeaf = (node: number, start: number, count: number, depth: number): void => {
    nodeU[node * 8 + 3] = start;
    nodeU[node * 8 + 7] = count;
    leafCount++;
    placed += count;
    if (depth > depthReached) depthReached = depth;
  };

  const makeInterior = (node: number, start: number, count: number, depth: number, mid: number): void => {
    const left = nodeCount;
    nodeCount += 2;
    nodeU[node * 8 + 3] = left;
    nodeU[node * 8 + 7] = 0;
    writeBounds(left, tmpL);
    writeBounds(left + 1, tmpR);
    // Right below left: the left subtree is finished first, so it is laid out first.
    push(left + 1, mid, start + count - mid, depth + 1, cbR);
    push(left, start, mid - start, depth + 1, cbL);
  };

  /** Object-median split along the widest centroid axis (index halves when all centroids coincide). */
  const medianSplit = (node: number, start: number, count: number, depth: number, cb: Float64Array): void => {
    const mid = start + (count >>> 1);
    const ex = cb[3]! - cb[0]!, ey = cb[4]! - cb[1]!, ez = cb[5]! - cb[2]!;
    if (ex > 0 || ey > 0 || ez > 0) {
      const axis = ex >= ey && ex >= ez ? 0 : ey >= ez ? 1 : 2;
      selectMedian(start, start + count, mid, axis);
    }
    scanBounds(start, mid - start, tmpL, cbL);
    scanBounds(mid, start + count - mid, tmpR, cbR);
    makeInterior(node, start, count, depth, mid);
  };

  const processNode = (node: number, start: number, count: number, depth: number, cb: Float64Array): void => {
    if (count <= maxLeafSize || depth >= maxDepth) {
      makeLeaf(node, start, count, depth);
      return;
    }
    const o = node * 8;
    const pMinX = nodeF[o]!, pMinY = nodeF[o + 1]!, pMinZ = nodeF[o + 2]!;
    const pMaxX = nodeF[o + 4]!, pMaxY = nodeF[o + 5]!, pMaxZ = nodeF[o + 6]!;
    const parentArea = halfArea(pMinX, pMinY, pMinZ, pMaxX, pMaxY, pMaxZ);
    // Costs are kept multiplied by the parent's area (no division, so zero-area nodes made of
    // degenerate triangles compare without NaN): leaf = C_i * N * A_P, split = C_t * A_P + C_i * (A_L N_L + A_R N_R).
    const leafCost = INTERSECTION_COST * count * parentArea;
    // Fewer bins than triangles cannot help; small nodes sweep fewer planes.
    const bins = Math.min(binCount, count);
    const k0 = cb[3]! > cb[0]! ? (bins * (1 - 1e-9)) / (cb[3]! - cb[0]!) : 0;
    const k1 = cb[4]! > cb[1]! ? (bins * (1 - 1e-9)) / (cb[4]! - cb[1]!) : 0;
    const k2 = cb[5]! > cb[2]! ? (bins * (1 - 1e-9)) / (cb[5]! - cb[2]!) : 0;
    const m0 = cb[0]!, m1 = cb[1]!, m2 = cb[2]!;
    let bestCost = Infinity;
    let bestAxis = -1;
    let bestPlane = 0;
    let bestLeftN = 0;
    if (k0 > 0 || k1 > 0 || k2 > 0) {
      binN.fill(0);
      for (let a = 0; a < 3; a++) {
        for (let b = 0; b < bins; b++) {
          const q = (a * binCount + b) * 6;
          binB[q] = Infinity; binB[q + 1] = Infinity; binB[q + 2] = Infinity;
          binB[q + 3] = -Infinity; binB[q + 4] = -Infinity; binB[q + 5] = -Infinity;
        }
      }
      // One pass bins every triangle on all three axes (Wald 2007, sec. 3.2: centroid binning).
      for (let s = start * 6, end = (start + count) * 6; s < end; s += 6) {
        const x0 = boxes[s]!, y0 = boxes[s + 1]!, z0 = boxes[s + 2]!, x1 = boxes[s + 3]!, y1 = boxes[s + 4]!, z1 = boxes[s + 5]!;
        if (k0 !== 0) {
          const f = k0 * ((x0 + x1) - m0);
          const q = f >= bins ? bins - 1 : f > 0 ? f | 0 : 0;
          binN[q]!++;
          const r = q * 6;
          if (x0 < binB[r]!) binB[r] = x0;
          if (y0 < binB[r + 1]!) binB[r + 1] = y0;
          if (z0 < binB[r + 2]!) binB[r + 2] = z0;
          if (x1 > binB[r + 3]!) binB[r + 3] = x1;
          if (y1 > binB[r + 4]!) binB[r + 4] = y1;
          if (z1 > binB[r + 5]!) binB[r + 5] = z1;
        }
        if (k1 !== 0) {
          const f = k1 * ((y0 + y1) - m1);
          const q = binCount + (f >= bins ? bins - 1 : f > 0 ? f | 0 : 0);
          binN[q]!++;
          const r = q * 6;
          if (x0 < binB[r]!) binB[r] = x0;
          if (y0 < binB[r + 1]!) binB[r + 1] = y0;
          if (z0 < binB[r + 2]!) binB[r + 2] = z0;
          if (x1 > binB[r + 3]!) binB[r + 3] = x1;
          if (y1 > binB[r + 4]!) binB[r + 4] = y1;
          if (z1 > binB[r + 5]!) binB[r + 5] = z1;
        }
        if (k2 !== 0) {
          const f = k2 * ((z0 + z1) - m2);
          const q = 2 * binCount + (f >= bins ? bins - 1 : f > 0 ? f | 0 : 0);
          binN[q]!++;
          const r = q * 6;
          if (x0 < binB[r]!) binB[r] = x0;
          if (y0 < binB[r + 1]!) binB[r + 1] = y0;
          if (z0 < binB[r + 2]!) binB[r + 2] = z0;
          if (x1 > binB[r + 3]!) binB[r + 3] = x1;
          if (y1 > binB[r + 4]!) binB[r + 4] = y1;
          if (z1 > binB[r + 5]!) binB[r + 5] = z1;
        }
      }
      // Sweep the bins-1 planes of each axis: suffix areas right to left, then prefix left to right.
      for (let a = 0; a < 3; a++) {
        if ((a === 0 ? k0 : a === 1 ? k1 : k2) === 0) continue;
        const base = a * binCount;
        let r0 = Infinity, r1 = Infinity, r2 = Infinity, r3 = -Infinity, r4 = -Infinity, r5 = -Infinity;
        let rn = 0;
        for (let b = bins - 1; b >= 1; b--) {
          const q = (base + b) * 6;
          if (binN[base + b]! > 0) {
            rn += binN[base + b]!;
            if (binB[q]! < r0) r0 = binB[q]!;
            if (binB[q + 1]! < r1) r1 = binB[q + 1]!;
            if (binB[q + 2]! < r2) r2 = binB[q + 2]!;
            if (binB[q + 3]! > r3) r3 = binB[q + 3]!;
            if (binB[q + 4]! > r4) r4 = binB[q + 4]!;
            if (binB[q + 5]! > r5) r5 = binB[q + 5]!;
          }
          rightN[b] = rn;
          rightArea[b] = rn > 0 ? halfArea(r0, r1, r2, r3, r4, r5) : 0;
        }
        let l0 = Infinity, l1 = Infinity, l2 = Infinity, l3 = -Infinity, l4 = -Infinity, l5 = -Infinity;
        let ln = 0;
        for (let b = 0; b < bins - 1; b++) {
          const q = (base + b) * 6;
          if (binN[base + b]! > 0) {
            ln += binN[base + b]!;
            if (binB[q]! < l0) l0 = binB[q]!;
            if (binB[q + 1]! < l1) l1 = binB[q + 1]!;
            if (binB[q + 2]! < l2) l2 = binB[q + 2]!;
            if (binB[q + 3]! > l3) l3 = binB[q + 3]!;
            if (binB[q + 4]! > l4) l4 = binB[q + 4]!;
            if (binB[q + 5]! > l5) l5 = binB[q + 5]!;
          }
          const rnb = rightN[b + 1]!;
          if (ln === 0 || rnb === 0) continue;
          const cost = TRAVERSAL_COST * parentArea + INTERSECTION_COST * (halfArea(l0, l1, l2, l3, l4, l5) * ln + rightArea[b + 1]! * rnb);
          if (cost < bestCost) {
            bestCost = cost;
            bestAxis = a;
            bestPlane = b + 1;
            bestLeftN = ln;
          }
        }
      }
    }

    const mustSplit = count > leafSizeCap;
    if (bestAxis < 0) {
      // No plane separates the centroids (all coincide, or one bin holds them all).
      if (!mustSplit) makeLeaf(node, start, count, depth);
      else medianSplit(node, start, count, depth, cb);
      return;
    }
    if (bestCost >= leafCost && !mustSplit) {
      // A leaf is cheaper than any split: Wald 2007's termination criterion.
      makeLeaf(node, start, count, depth);
      return;
    }
    // Depth budget: below this node there are maxDepth - depth - 1 levels for the larger child; with
    // median splits from there on, a child of N triangles reaches leaves of <= leafSizeCap only if
    // N <= leafSizeCap * 2^levels. A very lopsided SAH split that breaks this is replaced by a median
    // split, which keeps every leaf bounded however adversarial the input is.
    const larger = Math.max(bestLeftN, count - bestLeftN);
    if (larger > leafSizeCap * 2 ** (maxDepth - depth - 1)) {
      medianSplit(node, start, count, depth, cb);
      return;
    }

    // Partition slots by the chosen plane, recomputing each side's bounds and centroid bounds on the fly.
    const kk = bestAxis === 0 ? k0 : bestAxis === 1 ? k1 : k2;
    const mm = bestAxis === 0 ? m0 : bestAxis === 1 ? m1 : m2;
    // Centroid bounds of both sides in locals (no per-triangle array indirection).
    let l0 = Infinity, l1 = Infinity, l2 = Infinity, l3 = -Infinity, l4 = -Infinity, l5 = -Infinity;
    let r0 = Infinity, r1 = Infinity, r2 = Infinity, r3 = -Infinity, r4 = -Infinity, r5 = -Infinity;
    let i = start;
    let j = start + count - 1;
    while (i <= j) {
      const s = i * 6;
      const cx = boxes[s]! + boxes[s + 3]!, cy = boxes[s + 1]! + boxes[s + 4]!, cz = boxes[s + 2]! + boxes[s + 5]!;
      const f = kk * ((bestAxis === 0 ? cx : bestAxis === 1 ? cy : cz) - mm);
      const b = f >= bins ? bins - 1 : f > 0 ? f | 0 : 0;
      if (b < bestPlane) {
        if (cx < l0) l0 = cx;
        if (cy < l1) l1 = cy;
        if (cz < l2) l2 = cz;
        if (cx > l3) l3 = cx;
        if (cy > l4) l4 = cy;
        if (cz > l5) l5 = cz;
        i++;
      } else {
        if (cx < r0) r0 = cx;
        if (cy < r1) r1 = cy;
        if (cz < r2) r2 = cz;
        if (cx > r3) r3 = cx;
        if (cy > r4) r4 = cy;
        if (cz > r5) r5 = cz;
        swapSlots(i, j);
        j--;
      }
    }
    cbL[0] = l0; cbL[1] = l1; cbL[2] = l2; cbL[3] = l3; cbL[4] = l4; cbL[5] = l5;
    cbR[0] = r0; cbR[1] = r1; cbR[2] = r2; cbR[3] = r3; cbR[4] = r4; cbR[5] = r5;
    const mid = i;
    if (mid - start !== bestLeftN) throw new Error(`buildBvh: internal error, partition ${mid - start} != binned count ${bestLeftN}`);
    // Child boxes are unions of their bins.
    const base = bestAxis * binCount;
    tmpL[0] = tmpL[1] = tmpL[2] = tmpR[0] = tmpR[1] = tmpR[2] = Infinity;
    tmpL[3] = tmpL[4] = tmpL[5] = tmpR[3] = tmpR[4] = tmpR[5] = -Infinity;
    for (let b = 0; b < bins; b++) {
      if (binN[base + b] === 0) continue;
      const t = b < bestPlane ? tmpL : tmpR;
      const q = (base + b) * 6;
      for (let c = 0; c < 3; c++) {
        if (binB[q + c]! < t[c]!) t[c] = binB[q + c]!;
        if (binB[q + 3 + c]! > t[3 + c]!) t[3 + c] = binB[q + 3 + c]!;
      }
    }
    makeInterior(node, start, count, depth, mid);
  };

  const cbWork = new Float64Array(6);
  if (n === 0) {
    // An empty scene: one inverted root box that no slab test can enter (and a 0-count "interior"
    // root that traversal never reads, since it checks triangleCount first).
    tmpL[0] = tmpL[1] = tmpL[2] = 3.4e38;
    tmpL[3] = tmpL[4] = tmpL[5] = -3.4e38;
    writeBounds(0, tmpL);
  }

  const step = (deadline: number): boolean => {
    if (done) return true;
    const timed = deadline !== Infinity;
    // Prepass: triangle AABBs, in chunks so the async build can yield during it as well.
    while (boundsDone < n) {
      const end = Math.min(n, boundsDone + BOUNDS_CHUNK);
      for (let t = boundsDone; t < end; t++) {
        const p = t * 9;
        const s = t * 6;
        const ax = positions[p]!, ay = positions[p + 1]!, az = positions[p + 2]!;
        const bx = positions[p + 3]!, by = positions[p + 4]!, bz = positions[p + 5]!;
        const cx = positions[p + 6]!, cy = positions[p + 7]!, cz = positions[p + 8]!;
        boxes[s] = Math.min(ax, bx, cx);
        boxes[s + 1] = Math.min(ay, by, cy);
        boxes[s + 2] = Math.min(az, bz, cz);
        boxes[s + 3] = Math.max(ax, bx, cx);
        boxes[s + 4] = Math.max(ay, by, cy);
        boxes[s + 5] = Math.max(az, bz, cz);
        order[t] = t;
      }
      boundsDone = end;
      if (boundsDone === n) {
        scanBounds(0, n, tmpL, cbWork);
        writeBounds(0, tmpL);
        push(0, 0, n, 0, cbWork);
      }
      if (timed && performance.now() >= deadline) return false;
    }
    let sinceCheck = 0;
    while (sp > 0) {
      sp--;
      const node = stNode[sp]!;
      const start = stStart[sp]!;
      const count = stCount[sp]!;
      const depth = stDepth[sp]!;
      for (let k = 0; k < 6; k++) cbWork[k] = stCb[sp * 6 + k]!;
      processNode(node, start, count, depth, cbWork);
      // Reading the clock costs more than a small node; check every few nodes or after big ones.
      sinceCheck += count;
      if (timed && sinceCheck >= 2048) {
        sinceCheck = 0;
        if (performance.now() >= deadline) return sp === 0 ? (done = true) : false;
      }
    }
    done = true;
    return true;
  };

  const finish = (): BvhBuildResult => {
    if (!done) throw new Error('buildBvh: finish() before the build completed');
    const nodes = nodeBuffer.byteLength === nodeCount * BVH_NODE_BYTES ? nodeBuffer : nodeBuffer.slice(0, nodeCount * BVH_NODE_BYTES);
    const buildTimeMs = performance.now() - startTime;
    return {
      nodes,
      nodeCount,
      triangleOrder: order,
      depth: depthReached,
      leafCount,
      sahCost: computeSahCost(nodes, { nodeCount }),
      buildTimeMs,
    };
  };

  return { step, progress: () => (n === 0 ? 1 : placed / n), finish };
}

/**
 * Builds the BVH synchronously. On the main thread of a browser this blocks for the whole build
 * (roughly a second per million triangles); use `buildBvhAsync` or a Worker for large meshes.
 */
export function buildBvh(positions: Float32Array, options?: BvhBuildOptions): BvhBuildResult {
  const state = createBuildState(positions, options);
  state.step(Infinity);
  return state.finish();
}

type YieldFn = () => Promise<void>;

function eventLoopYield(): YieldFn {
  // `scheduler.yield()` (Prioritized Task Scheduling) resumes ahead of other queued tasks yet lets
  // input and rendering run; elsewhere a zero timeout gives the event loop one turn.
  const scheduler = (globalThis as { scheduler?: { yield?: () => Promise<void> } }).scheduler;
  if (scheduler && typeof scheduler.yield === 'function') return () => scheduler.yield!();
  return () => new Promise<void>((resolve) => setTimeout(resolve, 0));
}

/**
 * The same build as `buildBvh` (bit-identical output) run as a resumable loop over its explicit work
 * stack: it works for about `sliceMs` (default 8 ms, half a 60 Hz frame), then yields to the event
 * loop so a browser tab keeps handling input and painting while a large mesh builds. The work between
 * two yields is whole nodes, so the longest stretch is the root split of the mesh (a few tens of ms
 * for 1M triangles on a slow CPU); everything below it is finer grained. Moving the build off the
 * main thread entirely is the other option: call `buildBvh` (or this) inside a Worker and transfer
 * `nodes` and `triangleOrder.buffer` back.
 */
export async function buildBvhAsync(positions: Float32Array, options: BvhAsyncBuildOptions = {}): Promise<BvhBuildResult> {
  const { sliceMs = 8, signal, onProgress } = options;
  signal?.throwIfAborted();
  const state = createBuildState(positions, options);
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
