/** Small 3-vector helpers for the CPU light samplers (plain tuples: easy to mirror in WGSL). */
export type Vec3 = [number, number, number];

export const add = (a: readonly number[], b: readonly number[]): Vec3 => [a[0]! + b[0]!, a[1]! + b[1]!, a[2]! + b[2]!];
export const sub = (a: readonly number[], b: readonly number[]): Vec3 => [a[0]! - b[0]!, a[1]! - b[1]!, a[2]! - b[2]!];
export const scale = (a: readonly number[], s: number): Vec3 => [a[0]! * s, a[1]! * s, a[2]! * s];
export const mul = (a: readonly number[], b: readonly number[]): Vec3 => [a[0]! * b[0]!, a[1]! * b[1]!, a[2]! * b[2]!];
export const dot = (a: readonly number[], b: readonly number[]): number => a[0]! * b[0]! + a[1]! * b[1]! + a[2]! * b[2]!;
export const cross = (a: readonly number[], b: readonly number[]): Vec3 => [
  a[1]! * b[2]! - a[2]! * b[1]!,
  a[2]! * b[0]! - a[0]! * b[2]!,
  a[0]! * b[1]! - a[1]! * b[0]!,
];
export const length = (a: readonly number[]): number => Math.sqrt(dot(a, a));
export const distanceSquared = (a: readonly number[], b: readonly number[]): number => {
  const d = sub(a, b);
  return dot(d, d);
};
export function normalize(a: readonly number[]): Vec3 {
  const l = length(a);
  return l > 0 ? scale(a, 1 / l) : [0, 0, 0];
}

/** Rec. 709 luminance (the weights of `luminance()` in math.wgsl). */
export const luminance = (c: readonly number[]): number => 0.2126 * c[0]! + 0.7152 * c[1]! + 0.0722 * c[2]!;

/** sqrt(max(0, x)): rounding can push 1 - cos^2 slightly below zero. */
export const safeSqrt = (x: number): number => Math.sqrt(Math.max(0, x));

/**
 * An orthonormal basis around unit `n` (Duff et al. 2017, "Building an Orthonormal Basis, Revisited",
 * JCGT 6(1)): branch-free apart from the sign, the same formula a WGSL port uses.
 */
export function orthonormalBasis(n: readonly number[]): { t: Vec3; b: Vec3 } {
  const sign = n[2]! >= 0 ? 1 : -1;
  const a = -1 / (sign + n[2]!);
  const bb = n[0]! * n[1]! * a;
  return {
    t: [1 + sign * n[0]! * n[0]! * a, sign * bb, -sign * n[0]!],
    b: [bb, sign + n[1]! * n[1]! * a, -n[1]!],
  };
}
