/**
 * Packing of the build's output into the GPU records the traversal reads: `triangleLayout` records in
 * BVH slot order (so a leaf's triangles are contiguous) and the `bvhNodeLayout` node array.
 */
import { bvhNodeLayout, triangleLayout } from '../gpu-layout/records.ts';
import { fieldOf } from '../gpu-layout/struct-layout.ts';
import type { BvhBuildResult } from './bvh-builder.ts';

export interface TriangleMeta {
  /** Per original triangle; default 0. */
  materialIds?: Uint32Array;
  /** Per original triangle; default 0. */
  meshIndices?: Uint32Array;
}

// Word offsets of the fields, taken from the layout so a layout change cannot silently misplace them.
const W = {
  v0: fieldOf(triangleLayout, 'v0').offset / 4,
  materialId: fieldOf(triangleLayout, 'materialId').offset / 4,
  e1: fieldOf(triangleLayout, 'e1').offset / 4,
  meshIndex: fieldOf(triangleLayout, 'meshIndex').offset / 4,
  e2: fieldOf(triangleLayout, 'e2').offset / 4,
  sourceIndex: fieldOf(triangleLayout, 'sourceIndex').offset / 4,
};
const TRI_WORDS = triangleLayout.size / 4;

/**
 * `triangleLayout` records in BVH order: slot s holds original triangle `order[s]` as v0, e1 = v1 - v0,
 * e2 = v2 - v0 (Moller-Trumbore form; the edges are rounded to f32 here, once, so every consumer of
 * the buffer sees the same triangle), with sourceIndex = the original index. At least one record is
 * written, since WebGPU bindings cannot be empty.
 */
/**
 * A triangle whose edges are parallel to within 1e-6 rad (collinear "needles", zero area up to
 * rounding) has no visible surface, but Moller-Trumbore's determinant for it is f32 rounding noise
 * rather than 0, which yields hits at arbitrary t. Such triangles are stored with exactly zero
 * edges, so every traversal rejects them (det == 0) on the GPU and in the JS mirrors alike.
 */
function collapseNeedle(f: Float32Array, o: number): void {
  const ax = f[o + W.e1]!, ay = f[o + W.e1 + 1]!, az = f[o + W.e1 + 2]!;
  const bx = f[o + W.e2]!, by = f[o + W.e2 + 1]!, bz = f[o + W.e2 + 2]!;
  const cross = Math.hypot(ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx);
  if (cross <= 1e-6 * Math.hypot(ax, ay, az) * Math.hypot(bx, by, bz)) {
    for (let c = 0; c < 3; c++) {
      f[o + W.e1 + c] = 0;
      f[o + W.e2 + c] = 0;
    }
  }
}

export function packWavefrontTriangles(triangles: Float32Array, order: Uint32Array, meta: TriangleMeta = {}): ArrayBuffer {
  const count = order.length;
  if (triangles.length < count * 9) throw new RangeError(`packWavefrontTriangles: ${triangles.length / 9} triangles for an order of ${count}`);
  const buffer = new ArrayBuffer(Math.max(1, count) * triangleLayout.size);
  const f = new Float32Array(buffer);
  const u = new Uint32Array(buffer);
  const { materialIds, meshIndices } = meta;
  for (let s = 0; s < count; s++) {
    const t = order[s]!;
    const p = t * 9;
    const o = s * TRI_WORDS;
    const x = triangles[p]!, y = triangles[p + 1]!, z = triangles[p + 2]!;
    f[o + W.v0] = x;
    f[o + W.v0 + 1] = y;
    f[o + W.v0 + 2] = z;
    f[o + W.e1] = triangles[p + 3]! - x;
    f[o + W.e1 + 1] = triangles[p + 4]! - y;
    f[o + W.e1 + 2] = triangles[p + 5]! - z;
    f[o + W.e2] = triangles[p + 6]! - x;
    f[o + W.e2 + 1] = triangles[p + 7]! - y;
    f[o + W.e2 + 2] = triangles[p + 8]! - z;
    collapseNeedle(f, o);
    u[o + W.materialId] = materialIds ? materialIds[t]! : 0;
    u[o + W.meshIndex] = meshIndices ? meshIndices[t]! : 0;
    u[o + W.sourceIndex] = t;
  }
  return buffer;
}

/** The node records of a build, ready to upload (a copy of at least one record). */
export function packWavefrontBvhNodes(result: Pick<BvhBuildResult, 'nodes' | 'nodeCount'>): ArrayBuffer {
  const bytes = Math.max(1, result.nodeCount) * bvhNodeLayout.size;
  const out = new ArrayBuffer(bytes);
  new Uint8Array(out).set(new Uint8Array(result.nodes, 0, Math.min(bytes, result.nodes.byteLength)));
  return out;
}
