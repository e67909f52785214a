import type { AreaLight } from './area-lights.ts';
import {
  initSphericalRectangle,
  MAX_SPHERICAL_RECTANGLE_SOLID_ANGLE,
  MIN_SPHERICAL_RECTANGLE_SOLID_ANGLE,
  sampleSphericalRectangle,
} from './spherical-rectangle.ts';
import { add, dot, length, normalize, orthonormalBasis, safeSqrt, scale, sub, type Vec3 } from './vec3.ts';

/**
 * CPU reference samplers of the area lights, by solid angle where it is practical:
 * - rectangle: spherical rectangle sampling (Urena et al. 2013; spherical-rectangle.ts), pdf =
 *   1 / solid angle; outside pbrt-v4's [3e-4, 6.22] sr window it falls back to uniform area sampling;
 * - sphere: uniform sampling of the cone of directions it subtends (pbrt-v4 Sphere::Sample with a
 *   reference point, sec. 6.2.4), but parametrised by 1 - cos(theta) throughout, computed as
 *   sin^2 / (1 + cos) without cancellation: exact for tiny cones in f32 too, where pbrt switches to
 *   a Taylor approximation; from inside a two-sided sphere, uniform area sampling;
 * - disk: uniform area sampling (Shirley-Chiu concentric map) converted to solid angle,
 *   pdf = d^2 / (area |cos theta_light|).
 * Every sampler has a matching pdf(direction), the density MIS needs when a BSDF ray hits the light.
 * A one-sided light seen from behind gives no sample (pdf 0).
 *
 * WGSL port: no loops or recursion; the one branch decision (spherical vs area sampling for
 * rectangles) depends only on the light and the reference point, so sample and pdf take the same
 * branch. For spheres keep 1 - cos(theta_max) = sin^2 / (1 + sqrt(1 - sin^2)) in f32.
 */

export interface AreaLightSample {
  /** Unit direction from the reference point to `point`. */
  direction: Vec3;
  distance: number;
  point: Vec3;
  /** Solid-angle density; 0 = no sample. */
  pdf: number;
  /** Radiance emitted towards the reference point. */
  radiance: Vec3;
}

const NONE: AreaLightSample = { direction: [0, 0, 1], distance: 0, point: [0, 0, 0], pdf: 0, radiance: [0, 0, 0] };

function rectangleCorner(l: AreaLight): Vec3 {
  return sub(sub(l.center, scale(l.edgeU, 0.5)), scale(l.edgeV, 0.5));
}

/** Whether the emitting face of a rectangle or disk faces `p` (or the light is two-sided). */
function facesPoint(l: AreaLight, p: readonly number[]): boolean {
  const side = dot(sub(p, l.center), l.normal);
  return side > 0 || (l.twoSided && side < 0);
}

function solidAngleFromArea(areaPdf: number, distance: number, direction: readonly number[], normal: readonly number[]): number {
  const cos = Math.abs(dot(direction, normal));
  return cos > 0 ? (areaPdf * distance * distance) / cos : 0;
}

/** Cone subtended by a sphere seen from outside: axis, and 1 - cos(theta_max) computed stably. */
function sphereCone(l: AreaLight, p: readonly number[]): { axis: Vec3; dist: number; sin2Max: number; oneMinusCosMax: number } {
  const w = sub(l.center, p);
  const dist = length(w);
  const sin2Max = (l.radius * l.radius) / (dist * dist);
  // 1 - sqrt(1 - s) = s / (1 + sqrt(1 - s)) has no cancellation.
  const oneMinusCosMax = sin2Max / (1 + Math.sqrt(1 - sin2Max));
  return { axis: scale(w, 1 / dist), dist, sin2Max, oneMinusCosMax };
}

function concentricDisk(u1: number, u2: number): [number, number] {
  const a = 2 * u1 - 1;
  const b = 2 * u2 - 1;
  if (a === 0 && b === 0) return [0, 0];
  if (Math.abs(a) > Math.abs(b)) {
    const phi = (Math.PI / 4) * (b / a);
    return [a * Math.cos(phi), a * Math.sin(phi)];
  }
  const phi = Math.PI / 2 - (Math.PI / 4) * (a / b);
  return [b * Math.cos(phi), b * Math.sin(phi)];
}

function uniformSphere(u1: number, u2: number): Vec3 {
  const z = 1 - 2 * u1;
  const r = safeSqrt(1 - z * z);
  const phi = 2 * Math.PI * u2;
  return [r * Math.cos(phi), r * Math.sin(phi), z];
}

function toPoint(p: readonly number[], point: Vec3, pdf: number, radiance: Vec3): AreaLightSample {
  const d = sub(point, p);
  const distance = length(d);
  if (!(distance > 0) || !(pdf > 0) || !Number.isFinite(pdf)) return NONE;
  return { direction: scale(d, 1 / distance), distance, point, pdf, radiance: [...radiance] };
}

/** Samples a point on `light` as seen from `p` with uniform (u1, u2). */
export function sampleAreaLight(light: AreaLight, p: readonly number[], u1: number, u2: number): AreaLightSample {
  if (light.type === 'rectangle') {
    if (!facesPoint(light, p)) return NONE;
    const corner = rectangleCorner(light);
    const q = initSphericalRectangle(corner, light.edgeU, light.edgeV, p);
    if (q.solidAngle >= MIN_SPHERICAL_RECTANGLE_SOLID_ANGLE && q.solidAngle <= MAX_SPHERICAL_RECTANGLE_SOLID_ANGLE) {
      return toPoint(p, sampleSphericalRectangle(q, u1, u2), 1 / q.solidAngle, light.radiance);
    }
    const point = add(add(corner, scale(light.edgeU, u1)), scale(light.edgeV, u2));
    const s = toPoint(p, point, 1, light.radiance);
    return s.pdf > 0 ? { ...s, pdf: solidAngleFromArea(1 / light.area, s.distance, s.direction, light.normal) } : NONE;
  }
  if (light.type === 'disk') {
    if (!facesPoint(light, p)) return NONE;
    const [x, y] = concentricDisk(u1, u2);
    const point = add(light.center, add(scale(light.edgeU, x * light.radius), scale(light.edgeV, y * light.radius)));
    const s = toPoint(p, point, 1, light.radiance);
    return s.pdf > 0 ? { ...s, pdf: solidAngleFromArea(1 / light.area, s.distance, s.direction, light.normal) } : NONE;
  }
  const inside = dot(sub(p, light.center), sub(p, light.center)) <= light.radius * light.radius;
  if (inside) {
    if (!light.twoSided) return NONE;
    const n = uniformSphere(u1, u2);
    const s = toPoint(p, add(light.center, scale(n, light.radius)), 1, light.radiance);
    return s.pdf > 0 ? { ...s, pdf: solidAngleFromArea(1 / light.area, s.distance, s.direction, n) } : NONE;
  }
  // Uniform cone sampling, then the point of the sphere along the sampled direction (pbrt-v4).
  const cone = sphereCone(light, p);
  const sinThetaMax = Math.sqrt(cone.sin2Max);
  const oneMinusCos = u1 * cone.oneMinusCosMax;
  const cosTheta = 1 - oneMinusCos;
  const sin2Theta = oneMinusCos * (2 - oneMinusCos);
  // Angle alpha at the sphere's centre between -axis and the sampled point.
  const cosAlpha = sin2Theta / sinThetaMax + cosTheta * safeSqrt(1 - sin2Theta / cone.sin2Max);
  const sinAlpha = safeSqrt(1 - cosAlpha * cosAlpha);
  const phi = 2 * Math.PI * u2;
  const { t, b } = orthonormalBasis(cone.axis);
  const nLocal: Vec3 = [sinAlpha * Math.cos(phi), sinAlpha * Math.sin(phi), cosAlpha];
  // Surface normal at the sampled point: -(local z) faces the reference point.
  const n = add(add(scale(t, -nLocal[0]), scale(b, -nLocal[1])), scale(cone.axis, -nLocal[2]));
  return toPoint(p, add(light.center, scale(n, light.radius)), 1 / (2 * Math.PI * cone.oneMinusCosMax), light.radiance);
}

export interface AreaLightHit {
  distance: number;
  point: Vec3;
  /** Radiance emitted back along the ray (0 from a non-emitting face). */
  radiance: Vec3;
}

/** The first intersection of the ray (p, unit direction) with `light`, or null. */
export function intersectAreaLight(light: AreaLight, p: readonly number[], direction: readonly number[]): AreaLightHit | null {
  if (light.type === 'sphere') {
    const oc = sub(p, light.center);
    const bHalf = dot(oc, direction);
    // Discriminant in the form that avoids cancellation for distant spheres (Haines et al. 2019,
    // Ray Tracing Gems ch. 7): r^2 - |oc - (oc.d) d|^2.
    const perp = sub(oc, scale(direction, bHalf));
    const disc = light.radius * light.radius - dot(perp, perp);
    if (disc < 0) return null;
    const sq = Math.sqrt(disc);
    const c = dot(oc, oc) - light.radius * light.radius;
    const inside = c <= 0;
    const q = -bHalf + (bHalf <= 0 ? sq : -sq);
    const t0 = c / q;
    const t1 = q;
    const tNear = Math.min(t0, t1);
    const tFar = Math.max(t0, t1);
    const t = inside ? tFar : tNear;
    if (!(t > 0)) return null;
    const emits = inside ? light.twoSided : true;
    return { distance: t, point: add(p, scale(direction, t)), radiance: emits ? [...light.radiance] : [0, 0, 0] };
  }
  const denom = dot(direction, light.normal);
  if (denom === 0) return null;
  const t = dot(sub(light.center, p), light.normal) / denom;
  if (!(t > 0)) return null;
  const point = add(p, scale(direction, t));
  const rel = sub(point, light.center);
  if (light.type === 'rectangle') {
    const s = dot(rel, light.edgeU) / dot(light.edgeU, light.edgeU);
    const r = dot(rel, light.edgeV) / dot(light.edgeV, light.edgeV);
    if (Math.abs(s) > 0.5 || Math.abs(r) > 0.5) return null;
  } else if (dot(rel, rel) > light.radius * light.radius) {
    return null;
  }
  const front = denom < 0;
  return { distance: t, point, radiance: front || light.twoSided ? [...light.radiance] : [0, 0, 0] };
}

/** Solid-angle density with which `sampleAreaLight` returns unit `direction` from `p`. */
export function areaLightPdf(light: AreaLight, p: readonly number[], direction: readonly number[]): number {
  const hit = intersectAreaLight(light, p, direction);
  if (hit === null) return 0;
  if (light.type === 'rectangle') {
    if (!facesPoint(light, p)) return 0;
    const q = initSphericalRectangle(rectangleCorner(light), light.edgeU, light.edgeV, p);
    if (q.solidAngle >= MIN_SPHERICAL_RECTANGLE_SOLID_ANGLE && q.solidAngle <= MAX_SPHERICAL_RECTANGLE_SOLID_ANGLE) return 1 / q.solidAngle;
    return solidAngleFromArea(1 / light.area, hit.distance, direction, light.normal);
  }
  if (light.type === 'disk') {
    if (!facesPoint(light, p)) return 0;
    return solidAngleFromArea(1 / light.area, hit.distance, direction, light.normal);
  }
  const inside = dot(sub(p, light.center), sub(p, light.center)) <= light.radius * light.radius;
  if (inside) {
    if (!light.twoSided) return 0;
    return solidAngleFromArea(1 / light.area, hit.distance, direction, normalize(sub(hit.point, light.center)));
  }
  return 1 / (2 * Math.PI * sphereCone(light, p).oneMinusCosMax);
}
