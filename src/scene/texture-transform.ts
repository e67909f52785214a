import type { WavefrontTextureTransformInput } from './types.ts';

/** The two rows (a, b, tx), (c, d, ty) of a 2x3 uv transform: uv' = [a b; c d] uv + (tx, ty). */
export type UvTransformRows = readonly [number, number, number, number, number, number];

export const identityUvTransform: UvTransformRows = Object.freeze([1, 0, 0, 0, 1, 0] as const);

/**
 * KHR_texture_transform: matrix = translation * rotation * scale with the GLSL of the extension's
 * specification (rotation = mat3(cos, sin, 0, -sin, cos, 0, 0, 0, 1), column-major), so
 * u' = sx cos u - sy sin v + ox and v' = sx sin u + sy cos v + oy.
 */
export function textureTransformRows(t: Pick<WavefrontTextureTransformInput, 'offset' | 'rotation' | 'scale'> | undefined): UvTransformRows {
  if (!t) return identityUvTransform;
  const [ox, oy] = [t.offset?.[0] ?? 0, t.offset?.[1] ?? 0];
  const [sx, sy] = [t.scale?.[0] ?? 1, t.scale?.[1] ?? 1];
  const r = t.rotation ?? 0;
  const c = Math.cos(r);
  const s = Math.sin(r);
  return [c * sx, -s * sy, ox, s * sx, c * sy, oy];
}

export function applyUvTransform(m: UvTransformRows, u: number, v: number): [number, number] {
  return [m[0] * u + m[1] * v + m[2], m[3] * u + m[4] * v + m[5]];
}
