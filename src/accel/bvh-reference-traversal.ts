/**
 * JavaScript mirror of `bvh-traversal.wesl` over the same packed buffers (triangle primitives in
 * `primitiveLayout`, nodes in `bvhNodeLayout`), for tests and tools: closest hit with
 * Moller-Trumbore exactly as `intersect.wesl` writes it (two-sided, det threshold 1e-20, t in
 * (0, tMax)), any-hit that stops at the first occluder, and brute force over every triangle as the
 * ground truth. Arithmetic is in doubles on the stored f32 data, so it agrees with the GPU up to f32
 * rounding. The JS stack is unbounded: a reference has no stack to overflow.
 */
import { primitiveLayout } from '../gpu-layout/records.ts';

const TRI_WORDS = primitiveLayout.size / 4;
/** Word of the record's `primitive` field: the triangle's index within its mesh. */
const SOURCE_WORD = 7;

export interface ReferenceRay {
  origin: ArrayLike<number>;
  direction: ArrayLike<number>;
  /** Exclusive upper bound on t (default Infinity). */
  tMax?: number;
}

export interface ReferenceHit {
  t: number;
  /** BVH slot of the triangle. */
  slot: number;
  /** The record's `primitive`: the original triangle index for a single mesh. */
  sourceIndex: number;
  u: number;
  v: number;
}

export interface ReferenceScene {
  /** Packed `primitiveLayout` triangle records in BVH order. */
  triangles: ArrayBuffer;
  triangleCount: number;
  /** Packed `bvhNodeLayout` records; node 0 is the root. */
  nodes: ArrayBuffer;
}

const scratch = new Float64Array(3);

/** Moller-Trumbore (JGT 1997) on record `slot`; writes (t, u, v) to `out` and returns t, or -1. */
export function intersectPackedTriangle(f: Float32Array, slot: number, o: ArrayLike<number>, d: ArrayLike<number>, tMax: number, out: Float64Array = scratch): number {
  const b = slot * TRI_WORDS;
  const v0x = f[b]!, v0y = f[b + 1]!, v0z = f[b + 2]!;
  const e1x = f[b + 4]!, e1y = f[b + 5]!, e1z = f[b + 6]!;
  const e2x = f[b + 8]!, e2y = f[b + 9]!, e2z = f[b + 10]!;
  const dx = d[0]!, dy = d[1]!, dz = d[2]!;
  const px = dy * e2z - dz * e2y, py = dz * e2x - dx * e2z, pz = dx * e2y - dy * e2x;
  const det = e1x * px + e1y * py + e1z * pz;
  if (Math.abs(det) < 1e-20) return -1;
  const invDet = 1 / det;
  const sx = o[0]! - v0x, sy = o[1]! - v0y, sz = o[2]! - v0z;
  const u = (sx * px + sy * py + sz * pz) * invDet;
  if (u < 0 || u > 1) return -1;
  const qx = sy * e1z - sz * e1y, qy = sz * e1x - sx * e1z, qz = sx * e1y - sy * e1x;
  const v = (dx * qx + dy * qy + dz * qz) * invDet;
  if (v < 0 || u + v > 1) return -1;
  const t = (e2x * qx + e2y * qy + e2z * qz) * invDet;
  if (!(t > 0) || t >= tMax) return -1;
  out[0] = t;
  out[1] = u;
  out[2] = v;
  return t;
}

function safeInverse(d: number): number {
  // As safe_inverse_direction: keeps 0 * inf from producing NaN in the slab test.
  const tiny = 1e-30;
  return 1 / (Math.abs(d) < tiny ? (d >= 0 ? tiny : -tiny) : d);
}

/** Entry distance into node `node`'s box within [0, tMax], or Infinity (intersect_aabb). */
function enterBox(nf: Float32Array, node: number, o: ArrayLike<number>, ix: number, iy: number, iz: number, tMax: number): number {
  const b = node * 8;
  const ax = (nf[b]! - o[0]!) * ix, bx = (nf[b + 4]! - o[0]!) * ix;
  const ay = (nf[b + 1]! - o[1]!) * iy, by = (nf[b + 5]! - o[1]!) * iy;
  const az = (nf[b + 2]! - o[2]!) * iz, bz = (nf[b + 6]! - o[2]!) * iz;
  const tn = Math.max(Math.min(ax, bx), Math.min(ay, by), Math.min(az, bz), 0);
  const tf = Math.min(Math.max(ax, bx), Math.max(ay, by), Math.max(az, bz), tMax);
  return tn <= tf ? tn : Infinity;
}

/** Closest hit through the BVH, visiting the nearer child first like `trace_closest`. */
export function traceClosestReference(scene: ReferenceScene, ray: ReferenceRay): ReferenceHit | null {
  if (scene.triangleCount === 0) return null;
  const tf = new Float32Array(scene.triangles);
  const tu = new Uint32Array(scene.triangles);
  const nf = new Float32Array(scene.nodes);
  const nu = new Uint32Array(scene.nodes);
  const o = ray.origin;
  const d = ray.direction;
  const ix = safeInverse(d[0]!), iy = safeInverse(d[1]!), iz = safeInverse(d[2]!);
  let tBest = ray.tMax ?? Infinity;
  let best = -1;
  let bu = 0, bv = 0;
  const hit = new Float64Array(3);
  const stack: number[] = [];
  let sp = 0;
  if (enterBox(nf, 0, o, ix, iy, iz, tBest) === Infinity) return null;
  let node = 0;
  for (;;) {
    const count = nu[node * 8 + 7]!;
    const first = nu[node * 8 + 3]!;
    if (count > 0) {
      for (let s = first; s < first + count; s++) {
        if (intersectPackedTriangle(tf, s, o, d, tBest, hit) > 0) {
          tBest = hit[0]!;
          bu = hit[1]!;
          bv = hit[2]!;
          best = s;
        }
      }
      if (sp === 0) break;
      node = stack[--sp]!;
      continue;
    }
    const ta = enterBox(nf, first, o, ix, iy, iz, tBest);
    const tb = enterBox(nf, first + 1, o, ix, iy, iz, tBest);
    if (ta === Infinity && tb === Infinity) {
      if (sp === 0) break;
      node = stack[--sp]!;
    } else if (ta === Infinity) node = first + 1;
    else if (tb === Infinity) node = first;
    else {
      stack[sp++] = ta <= tb ? first + 1 : first;
      node = ta <= tb ? first : first + 1;
    }
  }
  if (best < 0) return null;
  return { t: tBest, slot: best, sourceIndex: tu[best * TRI_WORDS + SOURCE_WORD]!, u: bu, v: bv };
}

/** Whether anything is hit in (0, tMax), returning at the first hit found, like `trace_any`. */
export function traceAnyReference(scene: ReferenceScene, ray: ReferenceRay): boolean {
  if (scene.triangleCount === 0) return false;
  const tf = new Float32Array(scene.triangles);
  const nf = new Float32Array(scene.nodes);
  const nu = new Uint32Array(scene.nodes);
  const o = ray.origin;
  const d = ray.direction;
  const tMax = ray.tMax ?? Infinity;
  const ix = safeInverse(d[0]!), iy = safeInverse(d[1]!), iz = safeInverse(d[2]!);
  const stack: number[] = [0];
  let sp = 1;
  while (sp > 0) {
    const node = stack[--sp]!;
    if (enterBox(nf, node, o, ix, iy, iz, tMax) === Infinity) continue;
    const count = nu[node * 8 + 7]!;
    const first = nu[node * 8 + 3]!;
    if (count > 0) {
      for (let s = first; s < first + count; s++) if (intersectPackedTriangle(tf, s, o, d, tMax) > 0) return true;
    } else {
      stack[sp++] = first + 1;
      stack[sp++] = first;
    }
  }
  return false;
}

/** Ground truth: the closest hit over every triangle (first slot wins ties). */
export function bruteForceClosest(triangles: ArrayBuffer, triangleCount: number, ray: ReferenceRay): ReferenceHit | null {
  const tf = new Float32Array(triangles);
  const tu = new Uint32Array(triangles);
  const hit = new Float64Array(3);
  let tBest = ray.tMax ?? Infinity;
  let best = -1;
  let bu = 0, bv = 0;
  for (let s = 0; s < triangleCount; s++) {
    if (intersectPackedTriangle(tf, s, ray.origin, ray.direction, tBest, hit) > 0) {
      tBest = hit[0]!;
      bu = hit[1]!;
      bv = hit[2]!;
      best = s;
    }
  }
  if (best < 0) return null;
  return { t: tBest, slot: best, sourceIndex: tu[best * TRI_WORDS + SOURCE_WORD]!, u: bu, v: bv };
}

/** Ground truth any-hit over every triangle. */
export function bruteForceAny(triangles: ArrayBuffer, triangleCount: number, ray: ReferenceRay): boolean {
  const tf = new Float32Array(triangles);
  const tMax = ray.tMax ?? Infinity;
  for (let s = 0; s < triangleCount; s++) if (intersectPackedTriangle(tf, s, ray.origin, ray.direction, tMax) > 0) return true;
  return false;
}
