/**
 * Packing of the build's output into the GPU records the traversal reads: `primitiveLayout` records
 * in BVH slot order (so a leaf's primitives are contiguous), the `bvhNodeLayout` node array, and the
 * parent links the stackless fallback traversal walks.
 */
import { INDEX_NONE, PRIMITIVE_SHAPE_MASK, PRIMITIVE_SHAPE_TRIANGLE } from '../gpu-layout/constants.ts';
import { bvhNodeLayout, primitiveLayout } from '../gpu-layout/records.ts';
import { fieldOf } from '../gpu-layout/struct-layout.ts';
import type { BvhBuildResult } from './bvh-builder.ts';

export interface TriangleMeta {
  /** Per original triangle: the instance it belongs to (default 0). */
  instances?: Uint32Array;
  /** Per original triangle: its index within the instance mesh (default: the original index). */
  primitives?: Uint32Array;
}

// Word offsets of the fields, taken from the layout so a layout change cannot silently misplace them.
export const PRIMITIVE_FIELD_WORDS = {
  v0: fieldOf(primitiveLayout, 'v0').offset / 4,
  instance: fieldOf(primitiveLayout, 'instance').offset / 4,
  e1: fieldOf(primitiveLayout, 'e1').offset / 4,
  primitive: fieldOf(primitiveLayout, 'primitive').offset / 4,
  e2: fieldOf(primitiveLayout, 'e2').offset / 4,
  shape: fieldOf(primitiveLayout, 'shape').offset / 4,
};
export const PRIMITIVE_WORDS = primitiveLayout.size / 4;
const W = PRIMITIVE_FIELD_WORDS;

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

/**
 * The nine geometry floats of one record at word `o`: v0 then the edges (triangles) or the shape
 * parameters, `g[at..at + 9]`. Triangles' needles are collapsed (collapseNeedle).
 */
export function writePrimitiveGeometry(f: Float32Array, o: number, g: ArrayLike<number>, at: number, shape: number): void {
  for (let c = 0; c < 3; c++) {
    f[o + W.v0 + c] = g[at + c]!;
    f[o + W.e1 + c] = g[at + 3 + c]!;
    f[o + W.e2 + c] = g[at + 6 + c]!;
  }
  if ((shape & PRIMITIVE_SHAPE_MASK) === PRIMITIVE_SHAPE_TRIANGLE) collapseNeedle(f, o);
}

/** Primitives of any shape in BVH order: slot s holds flat primitive `order[s]`. */
export function packPrimitives(
  flat: { geometry: Float32Array; instance: Uint32Array; primitive: Uint32Array; shape: Uint32Array },
  order: Uint32Array,
): ArrayBuffer {
  const count = order.length;
  const buffer = new ArrayBuffer(Math.max(1, count) * primitiveLayout.size);
  const f = new Float32Array(buffer);
  const u = new Uint32Array(buffer);
  for (let s = 0; s < count; s++) {
    const k = order[s]!;
    const o = s * PRIMITIVE_WORDS;
    writePrimitiveGeometry(f, o, flat.geometry, 9 * k, flat.shape[k]!);
    u[o + W.instance] = flat.instance[k]!;
    u[o + W.primitive] = flat.primitive[k]!;
    u[o + W.shape] = flat.shape[k]!;
  }
  return buffer;
}

/**
 * Triangle `primitiveLayout` records in BVH order from a flat triangle soup (9 floats each): slot s
 * holds original triangle `order[s]` as v0, e1 = v1 - v0, e2 = v2 - v0 (Moller-Trumbore form; the
 * edges are rounded to f32 once, so every consumer sees the same triangle). At least one record.
 */
export function packWavefrontTriangles(triangles: Float32Array, order: Uint32Array, meta: TriangleMeta = {}): ArrayBuffer {
  const count = order.length;
  if (triangles.length < count * 9) throw new RangeError(`packWavefrontTriangles: ${triangles.length / 9} triangles for an order of ${count}`);
  const geometry = new Float32Array(Math.max(1, count) * 9);
  for (let t = 0; t < count; t++) {
    for (let c = 0; c < 3; c++) {
      const v0 = triangles[9 * t + c]!;
      geometry[9 * t + c] = v0;
      geometry[9 * t + 3 + c] = triangles[9 * t + 3 + c]! - v0;
      geometry[9 * t + 6 + c] = triangles[9 * t + 6 + c]! - v0;
    }
  }
  const primitive = meta.primitives ?? Uint32Array.from({ length: count }, (_, i) => i);
  return packPrimitives({ geometry, instance: meta.instances ?? new Uint32Array(count), primitive, shape: new Uint32Array(count) }, order);
}

/** The node records of a build, ready to upload (a copy of at least one record). */
export function packWavefrontBvhNodes(result: Pick<BvhBuildResult, 'nodes' | 'nodeCount'>): ArrayBuffer {
  const bytes = Math.max(1, result.nodeCount) * bvhNodeLayout.size;
  const out = new ArrayBuffer(bytes);
  new Uint8Array(out).set(new Uint8Array(result.nodes, 0, Math.min(bytes, result.nodes.byteLength)));
  return out;
}

/** The parent of every node (INDEX_NONE for the root), for stackless traversal. */
export function bvhParentLinks(nodes: ArrayBuffer, nodeCount: number): Uint32Array {
  const u = new Uint32Array(nodes);
  const parents = new Uint32Array(Math.max(1, nodeCount)).fill(INDEX_NONE);
  for (let i = 0; i < nodeCount; i++) {
    if (u[i * 8 + 7] !== 0) continue;
    const left = u[i * 8 + 3]!;
    parents[left] = i;
    parents[left + 1] = i;
  }
  return parents;
}
