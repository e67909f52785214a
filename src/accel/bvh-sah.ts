/**
 * SAH cost of a finished BVH (Goldsmith & Salmon 1987; MacDonald & Booth, "Heuristics for ray
 * tracing using space subdivision", 1990): the expected cost of a random ray that hits the root box,
 *
 *   C = sum_interior A(n)/A(root) * C_trav + sum_leaves A(n)/A(root) * N(n) * C_isect,
 *
 * with A the surface area. Lower is better; it is the figure binned SAH builders minimise greedily,
 * so it compares tree quality across builders independently of traversal code.
 */

export interface SahCostOptions {
  /** Records to read (default: all records of the buffer). */
  nodeCount?: number;
  /** Cost of visiting an interior node (default 1). */
  traversalCost?: number;
  /** Cost of one ray/triangle test (default 1). */
  intersectionCost?: number;
}

function surfaceHalfArea(f: Float32Array, minAt: number, maxAt: number): number {
  const dx = f[maxAt]! - f[minAt]!;
  const dy = f[maxAt + 1]! - f[minAt + 1]!;
  const dz = f[maxAt + 2]! - f[minAt + 2]!;
  if (!(dx >= 0 && dy >= 0 && dz >= 0)) return 0; // inverted (empty) box
  return dx * dy + dy * dz + dz * dx;
}

/**
 * Shared accumulation. Half areas are used throughout: only ratios to the root matter. A root of zero
 * area (every triangle degenerate and coincident) weighs every node as 1 instead of dividing by zero.
 */
function accumulate(rootArea: number, count: number, visit: (i: number) => [area: number, primitives: number], ct: number, ci: number): number {
  let sum = 0;
  for (let i = 0; i < count; i++) {
    const [area, primitives] = visit(i);
    const weight = rootArea > 0 ? area / rootArea : 1;
    sum += primitives > 0 ? weight * primitives * ci : weight * ct;
  }
  return sum;
}

/** SAH cost of packed `bvhNodeLayout` records (our builder's output); node 0 is the root. */
export function computeSahCost(nodes: ArrayBuffer, options: SahCostOptions = {}): number {
  const f = new Float32Array(nodes);
  const u = new Uint32Array(nodes);
  const count = options.nodeCount ?? nodes.byteLength / 32;
  if (count === 0) return 0;
  const ct = options.traversalCost ?? 1;
  const ci = options.intersectionCost ?? 1;
  const rootArea = surfaceHalfArea(f, 0, 4);
  const out: [number, number] = [0, 0];
  return accumulate(rootArea, count, (i) => {
    out[0] = surfaceHalfArea(f, i * 8, i * 8 + 4);
    out[1] = u[i * 8 + 7]!;
    return out;
  }, ct, ci);
}

/**
 * SAH cost of one three-mesh-bvh root buffer (`MeshBVH._roots[k]`, three-mesh-bvh 0.9.x), under the
 * same cost model. Its packed node (src/core/build/buildTree.js, utils/nodeBufferUtils.js) is 32
 * bytes: 6 float32 bounds (min xyz, max xyz); u32[6] = right child offset (interior) or first
 * triangle (leaf); u16[14] = triangle count and u16[15] = 0xffff on leaves. Every record in the
 * buffer is reachable (depth first, trimmed to the nodes written), so a linear pass visits the tree.
 */
export function computeThreeMeshBvhSahCost(root: ArrayBuffer, options: Omit<SahCostOptions, 'nodeCount'> = {}): number {
  const f = new Float32Array(root);
  const u16 = new Uint16Array(root);
  const count = root.byteLength / 32;
  if (count === 0) return 0;
  const ct = options.traversalCost ?? 1;
  const ci = options.intersectionCost ?? 1;
  const rootArea = surfaceHalfArea(f, 0, 3);
  const out: [number, number] = [0, 0];
  return accumulate(rootArea, count, (i) => {
    out[0] = surfaceHalfArea(f, i * 8, i * 8 + 3);
    out[1] = u16[i * 16 + 15] === 0xffff ? u16[i * 16 + 14]! : 0;
    return out;
  }, ct, ci);
}
