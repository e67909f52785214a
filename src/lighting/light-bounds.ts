import { cross, dot, length, normalize, safeSqrt, scale, sub, add, type Vec3 } from './vec3.ts';

/**
 * Spatial and directional bounds of a set of emitters, and their importance at a shading point:
 * Conty Estevez and Kulla 2018, "Importance Sampling of Many Lights with Adaptive Tree Splitting"
 * (HPG), sec. 4.1 (the orientation cone (axis, theta_o, theta_e) and eq. 3), in the formulation of
 * pbrt-v4's LightBounds (4th ed., sec. 12.6.3), with two deliberate differences:
 * - `phi` bounds the radiant *intensity* (luminance-weighted, W/sr-like: L x area for a planar
 *   emitter, L x pi r^2 for a sphere, I for point and spot lights), not the flux, so that phi x cos /
 *   d^2 bounds the irradiance an emitter can deliver whatever its kind (with flux, a point light
 *   would weigh 4 times an area light of the same peak intensity);
 * - the distance is clamped to at least a quarter of the bounding sphere's radius R (and 1e-20), so
 *   the importance stays finite at a cluster's centre. pbrt clamps d^2 to the half diagonal, a
 *   length, which depends on the scene's unit; clamping to R itself flattens every large cluster the
 *   point is inside and loses most of the tree's benefit (measured in test/lighting/light-tree.test.ts:
 *   10,000 triangles, variance ratio over power sampling 3.3 with d >= R, 54 with d >= R / 4 or no
 *   clamp). Emitters spread through a ball of radius R around p give about 3 phi / R^2, so R / 4
 *   only guards the singularity.
 * The importance is conservative: it is 0 only where no emitter in the bounds can illuminate the
 * point (every emitter faces away), which keeps light-tree sampling unbiased.
 */
export interface LightBounds {
  boundsMin: Vec3;
  boundsMax: Vec3;
  /** Unit axis of the cone bounding the emitters' normals (or spot directions). */
  axis: Vec3;
  /** cos of the spread of the normals around `axis` (-1: all directions). */
  cosThetaO: number;
  /** cos of the emission spread around each normal (0: hemisphere, planar emitters). */
  cosThetaE: number;
  /** Luminance-weighted bound of the radiant intensity (see above); 0 = emits nothing. */
  phi: number;
  /** Emits on both sides of the normals (the cone applies to +-axis). */
  twoSided: boolean;
}

export function unionBounds(a: LightBounds, b: LightBounds): LightBounds {
  if (!(a.phi > 0)) return b;
  if (!(b.phi > 0)) return a;
  const cone = unionCones(a.axis, a.cosThetaO, b.axis, b.cosThetaO);
  return {
    boundsMin: [Math.min(a.boundsMin[0], b.boundsMin[0]), Math.min(a.boundsMin[1], b.boundsMin[1]), Math.min(a.boundsMin[2], b.boundsMin[2])],
    boundsMax: [Math.max(a.boundsMax[0], b.boundsMax[0]), Math.max(a.boundsMax[1], b.boundsMax[1]), Math.max(a.boundsMax[2], b.boundsMax[2])],
    axis: cone.axis,
    cosThetaO: cone.cosTheta,
    cosThetaE: Math.min(a.cosThetaE, b.cosThetaE),
    phi: a.phi + b.phi,
    twoSided: a.twoSided || b.twoSided,
  };
}

/** Smallest cone containing two cones (pbrt-v4 DirectionCone Union; Conty and Kulla, Alg. 1). */
export function unionCones(wa: Vec3, cosA: number, wb: Vec3, cosB: number): { axis: Vec3; cosTheta: number } {
  const thetaA = Math.acos(Math.min(1, Math.max(-1, cosA)));
  const thetaB = Math.acos(Math.min(1, Math.max(-1, cosB)));
  const thetaD = angleBetween(wa, wb);
  if (Math.min(thetaD + thetaB, Math.PI) <= thetaA) return { axis: wa, cosTheta: cosA };
  if (Math.min(thetaD + thetaA, Math.PI) <= thetaB) return { axis: wb, cosTheta: cosB };
  const thetaO = (thetaA + thetaD + thetaB) / 2;
  if (thetaO >= Math.PI) return { axis: wa, cosTheta: -1 };
  const thetaR = thetaO - thetaA;
  const wr = cross(wa, wb);
  if (dot(wr, wr) === 0) return { axis: wa, cosTheta: -1 };
  // Rotate wa by thetaR towards wb about k = wr / |wr| (Rodrigues; k is orthogonal to wa).
  const k = normalize(wr);
  const axis = normalize(add(scale(wa, Math.cos(thetaR)), scale(cross(k, wa), Math.sin(thetaR))));
  return { axis, cosTheta: Math.cos(thetaO) };
}

/** Angle between unit vectors, accurate near 0 and pi (pbrt-v4 AngleBetween). */
export function angleBetween(a: Vec3, b: Vec3): number {
  if (dot(a, b) < 0) return Math.PI - 2 * Math.asin(Math.min(1, length(add(a, b)) / 2));
  return 2 * Math.asin(Math.min(1, length(sub(b, a)) / 2));
}

/** cos(max(0, a - b)) from the sines and cosines of a and b. */
function cosSubClamped(sinA: number, cosA: number, sinB: number, cosB: number): number {
  if (cosA > cosB) return 1;
  return cosA * cosB + sinA * sinB;
}

/** sin(max(0, a - b)). */
function sinSubClamped(sinA: number, cosA: number, sinB: number, cosB: number): number {
  if (cosA > cosB) return 0;
  return sinA * cosB - cosA * sinB;
}

/**
 * Importance of the bounds at point `p` with surface normal `n` ([0, 0, 0] for a point in a medium):
 * phi x cos(theta') / d^2 x |cos(theta_i')|, where theta' = max(0, theta_w - theta_o - theta_b) and
 * 0 when theta' >= theta_e; theta_b bounds the angle the box subtends at p (Conty and Kulla eq. 3).
 *
 * WGSL port: straight-line code, all in cosines and sines (no acos).
 */
export function lightBoundsImportance(b: LightBounds, p: readonly number[], n: readonly number[]): number {
  if (!(b.phi > 0)) return 0;
  const pc: Vec3 = [(b.boundsMin[0] + b.boundsMax[0]) / 2, (b.boundsMin[1] + b.boundsMax[1]) / 2, (b.boundsMin[2] + b.boundsMax[2]) / 2];
  const halfDiagonal2 = dot(sub(b.boundsMax, b.boundsMin), sub(b.boundsMax, b.boundsMin)) / 4;
  const toPoint = sub(p, pc);
  const dist2 = dot(toPoint, toPoint);
  const d2 = Math.max(dist2, halfDiagonal2 / 16, 1e-20);
  const wi = dist2 > 0 ? scale(toPoint, 1 / Math.sqrt(dist2)) : ([0, 0, 1] as Vec3);
  let cosThetaW = dot(b.axis, wi);
  if (b.twoSided) cosThetaW = Math.abs(cosThetaW);
  const sinThetaW = safeSqrt(1 - cosThetaW * cosThetaW);
  // Cone of directions from p that reach the box's bounding sphere.
  const cosThetaB = dist2 < halfDiagonal2 ? -1 : safeSqrt(1 - halfDiagonal2 / dist2);
  const sinThetaB = safeSqrt(1 - cosThetaB * cosThetaB);
  const sinThetaO = safeSqrt(1 - b.cosThetaO * b.cosThetaO);
  const cosThetaX = cosSubClamped(sinThetaW, cosThetaW, sinThetaO, b.cosThetaO);
  const sinThetaX = sinSubClamped(sinThetaW, cosThetaW, sinThetaO, b.cosThetaO);
  const cosThetaP = cosSubClamped(sinThetaX, cosThetaX, sinThetaB, cosThetaB);
  if (cosThetaP <= b.cosThetaE) return 0;
  let importance = (b.phi * cosThetaP) / d2;
  if (n[0] !== 0 || n[1] !== 0 || n[2] !== 0) {
    const cosThetaI = Math.abs(dot(wi, n));
    const sinThetaI = safeSqrt(1 - cosThetaI * cosThetaI);
    importance *= cosSubClamped(sinThetaI, cosThetaI, sinThetaB, cosThetaB);
  }
  return Math.max(importance, 0);
}
