import { safeSqrt, type Vec3 } from './vec3.ts';

/**
 * Equirectangular (latitude-longitude) mapping, three.js's convention with +Y up:
 *   u = fract(atan2(d.z, d.x) / (2 pi) + 0.5 + rotation / (2 pi)),  v = theta / pi = acos(d.y) / pi.
 * Row 0 of an environment map is v = 0 (the +Y zenith); column 0 starts at u = 0.
 *
 * WGSL port: compute theta as atan2(length(d.xz), d.y) rather than acos(d.y), and sin(theta) as
 * length(d.xz) rather than sqrt(1 - y^2): both stay accurate in f32 next to the poles, where the
 * acos / sqrt forms lose all their digits.
 */

const TWO_PI = 2 * Math.PI;

/** fract(x) in [0, 1): x - floor(x), with the rounding case x - floor(x) == 1 folded to 0. */
export function fract(x: number): number {
  const f = x - Math.floor(x);
  return f >= 1 ? 0 : f;
}

/** (u, v) in [0, 1)^2 x [0, 1] of unit direction `d`. */
export function directionToEquirectUv(d: readonly number[], rotationRadians = 0): [number, number] {
  const sinTheta = Math.hypot(d[0]!, d[2]!);
  const theta = Math.atan2(sinTheta, d[1]!);
  const phi = Math.atan2(d[2]!, d[0]!);
  return [fract(phi / TWO_PI + 0.5 + rotationRadians / TWO_PI), theta / Math.PI];
}

/** Unit direction of (u, v); the inverse of `directionToEquirectUv`. */
export function equirectUvToDirection(u: number, v: number, rotationRadians = 0): Vec3 {
  const theta = Math.PI * v;
  const phi = TWO_PI * u - Math.PI - rotationRadians;
  const sinTheta = Math.sin(theta);
  return [sinTheta * Math.cos(phi), Math.cos(theta), sinTheta * Math.sin(phi)];
}

/** sin(theta) of a unit direction, accurate near the poles. */
export function equirectSinTheta(d: readonly number[]): number {
  return Math.hypot(d[0]!, d[2]!);
}

/**
 * Solid-angle density from a density over (u, v) in [0, 1]^2: d omega = 2 pi^2 sin(theta) du dv,
 * so pdf_omega = pdf_uv / (2 pi^2 sin(theta)); 0 at the poles, where the map has no area.
 */
export function uvPdfToSolidAngle(pdfUv: number, sinTheta: number): number {
  return sinTheta > 0 ? pdfUv / (2 * Math.PI * Math.PI * sinTheta) : 0;
}

/** The inverse: pdf_uv = pdf_omega * 2 pi^2 sin(theta). */
export function solidAnglePdfToUv(pdfSolidAngle: number, sinTheta: number): number {
  return pdfSolidAngle * 2 * Math.PI * Math.PI * safeSqrt(sinTheta * sinTheta);
}
