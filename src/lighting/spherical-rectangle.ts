import { cross, dot, length, scale, sub, type Vec3 } from './vec3.ts';

/**
 * Uniform sampling of the solid angle subtended by a rectangle: Urena, Fajardo, King 2013, "An
 * Area-Preserving Parametrization for Spherical Rectangles" (EGSR), section 4 and the algorithm of
 * its Figure 6. The rectangle is corner `s` with orthogonal edges `ex`, `ey`; `o` the reference
 * point. pdf = 1 / solidAngle for every direction through the rectangle.
 *
 * WGSL port: straight-line code (no loops). In f32 the solid angle g0 + g1 + g2 + g3 - 2 pi cancels
 * for far rectangles, so callers fall back to area sampling below MIN_SPHERICAL_RECTANGLE_SOLID_ANGLE
 * (pbrt-v4's threshold, the same decision in `pdf` and `sample`).
 */
export interface SphericalRectangle {
  o: Vec3;
  x: Vec3;
  y: Vec3;
  /** Unit normal of the local frame, flipped so that z0 <= 0 (points away from the rectangle). */
  z: Vec3;
  z0: number;
  x0: number;
  y0: number;
  x1: number;
  y1: number;
  b0: number;
  b1: number;
  k: number;
  /** Solid angle subtended at `o`. */
  solidAngle: number;
}

/** pbrt-v4's bounds (lights.h): below, f32 loses the solid angle; above, the parametrization degrades. */
export const MIN_SPHERICAL_RECTANGLE_SOLID_ANGLE = 3e-4;
export const MAX_SPHERICAL_RECTANGLE_SOLID_ANGLE = 6.22;

export function initSphericalRectangle(s: readonly number[], ex: readonly number[], ey: readonly number[], o: readonly number[]): SphericalRectangle {
  const exl = length(ex);
  const eyl = length(ey);
  const x = scale(ex, 1 / exl);
  const y = scale(ey, 1 / eyl);
  let z = cross(x, y);
  const d = sub(s, o);
  let z0 = dot(d, z);
  if (z0 > 0) {
    z = scale(z, -1);
    z0 = -z0;
  }
  const x0 = dot(d, x);
  const y0 = dot(d, y);
  const x1 = x0 + exl;
  const y1 = y0 + eyl;
  // Normals of the four great-circle edges, in the local frame (paper, eq. 5 and Fig. 6).
  const n0 = unit([0, z0, -y0]);
  const n1 = unit([-z0, 0, x1]);
  const n2 = unit([0, -z0, y1]);
  const n3 = unit([z0, 0, -x0]);
  const g0 = Math.acos(clamp1(-dot(n0, n1)));
  const g1 = Math.acos(clamp1(-dot(n1, n2)));
  const g2 = Math.acos(clamp1(-dot(n2, n3)));
  const g3 = Math.acos(clamp1(-dot(n3, n0)));
  const k = 2 * Math.PI - g2 - g3;
  return { o: [o[0]!, o[1]!, o[2]!], x, y, z, z0, x0, y0, x1, y1, b0: n0[2], b1: n2[2], k, solidAngle: g0 + g1 - k };
}

/** The point on the rectangle in direction (u, v) of the area-preserving map. */
export function sampleSphericalRectangle(q: SphericalRectangle, u: number, v: number): Vec3 {
  const au = u * q.solidAngle + q.k;
  const fu = (Math.cos(au) * q.b0 - q.b1) / Math.sin(au);
  let cu = (1 / Math.sqrt(fu * fu + q.b0 * q.b0)) * (fu > 0 ? 1 : -1);
  cu = clamp1(cu);
  let xu = -(cu * q.z0) / Math.sqrt(Math.max(1e-300, 1 - cu * cu));
  xu = Math.min(q.x1, Math.max(q.x0, xu));
  const dd = Math.sqrt(xu * xu + q.z0 * q.z0);
  const h0 = q.y0 / Math.sqrt(dd * dd + q.y0 * q.y0);
  const h1 = q.y1 / Math.sqrt(dd * dd + q.y1 * q.y1);
  const hv = h0 + v * (h1 - h0);
  const hv2 = hv * hv;
  const yv = hv2 < 1 - 1e-12 ? (hv * dd) / Math.sqrt(1 - hv2) : q.y1;
  return [
    q.o[0] + xu * q.x[0] + yv * q.y[0] + q.z0 * q.z[0],
    q.o[1] + xu * q.x[1] + yv * q.y[1] + q.z0 * q.z[1],
    q.o[2] + xu * q.x[2] + yv * q.y[2] + q.z0 * q.z[2],
  ];
}

function unit(v: Vec3): Vec3 {
  return scale(v, 1 / length(v));
}

function clamp1(x: number): number {
  return Math.min(1, Math.max(-1, x));
}
