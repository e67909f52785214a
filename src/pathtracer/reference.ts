import type { WavefrontPathTracingComputeConfig } from './config.ts';

/**
 * Deterministic JavaScript mirrors of the WGSL camera and triangle math (camera.wesl,
 * accel/intersect.wesl), evaluated in float32 with Math.fround at each step, so tools and tests can check
 * GPU primary hits without a device.
 */
const f = Math.fround;

export interface WavefrontReferenceRay {
  origin: [number, number, number];
  direction: [number, number, number];
}

export interface WavefrontReferenceTriangle {
  v0: readonly number[];
  v1: readonly number[];
  v2: readonly number[];
}

export interface WavefrontReferenceHit {
  t: number;
  u: number;
  v: number;
}

export interface WavefrontReferenceTraceResult {
  hit: boolean;
  /** Index of the closest triangle, -1 on a miss. */
  triangle: number;
  t: number;
  u: number;
  v: number;
  /** Environment radiance seen on a miss (black on a hit). */
  environment: [number, number, number];
}

function sub(a: readonly number[], b: readonly number[]): number[] {
  return [f(a[0]! - b[0]!), f(a[1]! - b[1]!), f(a[2]! - b[2]!)];
}
function cross(a: readonly number[], b: readonly number[]): number[] {
  return [f(f(a[1]! * b[2]!) - f(a[2]! * b[1]!)), f(f(a[2]! * b[0]!) - f(a[0]! * b[2]!)), f(f(a[0]! * b[1]!) - f(a[1]! * b[0]!))];
}
function dot(a: readonly number[], b: readonly number[]): number {
  return f(f(f(a[0]! * b[0]!) + f(a[1]! * b[1]!)) + f(a[2]! * b[2]!));
}

/** The camera ray through continuous pixel coordinates `pixel + jitter` (top-left origin, y down). */
export function createWavefrontReferenceRay(
  config: Pick<WavefrontPathTracingComputeConfig, 'width' | 'height' | 'camera'>,
  options: { pixel?: readonly [number, number]; jitter?: readonly [number, number] } = {},
): WavefrontReferenceRay {
  const [px, py] = options.pixel ?? [config.width / 2 - 0.5, config.height / 2 - 0.5];
  const [jx, jy] = options.jitter ?? [0.5, 0.5];
  const c = config.camera;
  const x = f(f(px) + f(jx));
  const y = f(f(py) + f(jy));
  const ndcX = f(f(f(2 * x) / f(config.width)) - 1);
  const ndcY = f(1 - f(f(2 * y) / f(config.height)));
  const aspect = f(config.width / config.height);
  if (c.kind === 'orthographic') {
    const h = f(c.orthographicHalfHeight);
    const ox = f(f(ndcX * h) * aspect);
    const oy = f(ndcY * h);
    const origin = [0, 1, 2].map((i) => f(f(f(c.position[i]!) + f(ox * f(c.right[i]!))) + f(oy * f(c.trueUp[i]!))));
    return { origin: [origin[0]!, origin[1]!, origin[2]!], direction: [f(c.forward[0]), f(c.forward[1]), f(c.forward[2])] };
  }
  const tan = f(c.tanHalfFovY);
  const sx = f(f(ndcX * tan) * aspect);
  const sy = f(ndcY * tan);
  const d = [0, 1, 2].map((i) => f(f(f(c.forward[i]!) + f(sx * f(c.right[i]!))) + f(sy * f(c.trueUp[i]!))));
  const len = Math.hypot(d[0]!, d[1]!, d[2]!);
  return { origin: [f(c.position[0]), f(c.position[1]), f(c.position[2])], direction: [f(d[0]! / len), f(d[1]! / len), f(d[2]! / len)] };
}

/** Moller-Trumbore as in intersect.wesl: two-sided, t in (0, tMax). */
export function intersectWavefrontReferenceTriangle(
  ray: WavefrontReferenceRay,
  triangle: WavefrontReferenceTriangle,
  options: { tMax?: number } = {},
): WavefrontReferenceHit | null {
  const tMax = options.tMax ?? Infinity;
  const v0 = triangle.v0.map(f);
  const e1 = sub(triangle.v1.map(f), v0);
  const e2 = sub(triangle.v2.map(f), v0);
  const p = cross(ray.direction, e2);
  const det = dot(e1, p);
  if (Math.abs(det) < 1e-20) return null;
  const invDet = f(1 / det);
  const s = sub(ray.origin, v0);
  const u = f(dot(s, p) * invDet);
  if (u < 0 || u > 1) return null;
  const q = cross(s, e1);
  const v = f(dot(ray.direction, q) * invDet);
  if (v < 0 || f(u + v) > 1) return null;
  const t = f(dot(e2, q) * invDet);
  if (t <= 0 || t >= tMax) return null;
  return { t, u, v };
}

/** Brute-force closest hit over `triangles`; on a miss, reports the configured environment. */
export function traceWavefrontReferenceTriangles(
  config: Partial<Pick<WavefrontPathTracingComputeConfig, 'environment'>>,
  ray: WavefrontReferenceRay,
  triangles: readonly WavefrontReferenceTriangle[],
  options: { tMax?: number } = {},
): WavefrontReferenceTraceResult {
  let best: WavefrontReferenceTraceResult = { hit: false, triangle: -1, t: options.tMax ?? Infinity, u: 0, v: 0, environment: [...(config.environment ?? [0, 0, 0])] };
  triangles.forEach((tri, i) => {
    const h = intersectWavefrontReferenceTriangle(ray, tri, { tMax: best.t });
    if (h) best = { hit: true, triangle: i, t: h.t, u: h.u, v: h.v, environment: [0, 0, 0] };
  });
  if (!best.hit) best.t = -1;
  return best;
}
