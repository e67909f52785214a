/**
 * KHR_texture_transform (glTF extension, "Overview" and "glTF Schema Updates"): uv' = T R S uv,
 * with T the offset, S the scale and R the rotation, as the 2x3 rows TextureBinding stores.
 *
 * Rotation sign: the extension rotates UVs "counter-clockwise" in uv space, whose v axis points
 * down (glTF's uv origin is the image's upper left corner), so
 *   R = [ cos  sin ]
 *       [ -sin cos ]
 * This is the matrix the extension's "Example JSON" needs (offset [0, 1], rotation pi/2, scale
 * [0.5, 0.5] shows the lower left quadrant rotated clockwise 90 degrees) and the one glTF viewers
 * use; the extension's GLSL snippet read as column-major GLSL would give the opposite sign.
 */
import { requireFiniteNumber, requireVec } from '../errors/validate.ts';
import type { TextureTransformRows, Vec3Row, WavefrontTextureTransformInput } from './texture-refs.ts';

export type { TextureTransformRows, Vec3Row };



/** The identity transform (no KHR_texture_transform). */
export function identityTextureTransform(): TextureTransformRows {
  return { transform0: [1, 0, 0], transform1: [0, 1, 0] };
}

/**
 * The uv transform rows of a KHR_texture_transform (defaults: offset [0, 0], rotation 0, scale
 * [1, 1]); bad values are INVALID_MATERIAL errors naming `field` (e.g.
 * `materials[0].baseColorTexture.transform`).
 */
export function textureTransformMatrix(t: WavefrontTextureTransformInput | undefined, field = 'transform'): TextureTransformRows {
  if (t === undefined) return identityTextureTransform();
  const [ox, oy] = t.offset === undefined ? [0, 0] : requireVec(t.offset, 2, `${field}.offset`, 'INVALID_MATERIAL');
  const rotation = t.rotation === undefined ? 0 : requireFiniteNumber(t.rotation, `${field}.rotation`, 'INVALID_MATERIAL');
  const [sx, sy] = t.scale === undefined ? [1, 1] : requireVec(t.scale, 2, `${field}.scale`, 'INVALID_MATERIAL');
  const c = Math.cos(rotation);
  const s = Math.sin(rotation);
  // T R S: the columns of R S are R's columns scaled by sx and sy.
  return {
    transform0: [c * sx, s * sy, ox!],
    transform1: [-s * sx, c * sy, oy!],
  };
}

/** Applies the rows to a uv (the same arithmetic as texture-sampling.wesl `transform_uv`). */
export function applyTextureTransform(rows: TextureTransformRows, u: number, v: number): [number, number] {
  const [a, b, tx] = rows.transform0;
  const [c, d, ty] = rows.transform1;
  return [a * u + b * v + tx, c * u + d * v + ty];
}
