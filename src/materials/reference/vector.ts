/** Small double-precision vector helpers for the CPU references (local shading frame, z = normal). */
export { luminance } from '../../lighting/emissive-lights.ts';

export type Vec3 = readonly [number, number, number];

export const dot = (a: Vec3, b: Vec3): number => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
export const add = (a: Vec3, b: Vec3): Vec3 => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
export const scale = (a: Vec3, s: number): Vec3 => [a[0] * s, a[1] * s, a[2] * s];
export const length = (a: Vec3): number => Math.hypot(a[0], a[1], a[2]);
export const normalize = (a: Vec3): Vec3 => scale(a, 1 / length(a));
export const neg = (a: Vec3): Vec3 => [-a[0], -a[1], -a[2]];
export const cross = (a: Vec3, b: Vec3): Vec3 => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
export const maxComponent = (a: Vec3): number => Math.max(a[0], a[1], a[2]);
/** Mirror image of w through the tangent plane (thin-walled transmission). */
export const mirrorZ = (w: Vec3): Vec3 => [w[0], w[1], -w[2]];

/** An orthonormal frame around unit n (any tangent: isotropic lobes only). */
export interface LocalFrame {
  readonly t: Vec3;
  readonly b: Vec3;
  readonly n: Vec3;
}

export function frameAround(n: Vec3): LocalFrame {
  const a: Vec3 = Math.abs(n[0]) > 0.9 ? [0, 1, 0] : [1, 0, 0];
  const t = normalize(cross(a, n));
  return { t, b: cross(n, t), n };
}

export const toLocal = (f: LocalFrame, v: Vec3): Vec3 => [dot(v, f.t), dot(v, f.b), dot(v, f.n)];
