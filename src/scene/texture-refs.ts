// How materials refer to textures, as types with no dependencies: the material-extension registry
// (src/materials/extensions) sits below the scene and names these in its entries.
export type Vec2Input = readonly [number, number] | readonly number[];

/** KHR_texture_transform: uv' = T(offset) R(rotation) S(scale) uv, applied before wrapping. */
export interface WavefrontTextureTransformInput {
  /** Default [0, 0]. */
  offset?: Vec2Input;
  /** Radians, counter-clockwise in uv space; default 0. */
  rotation?: number;
  /** Default [1, 1]. */
  scale?: Vec2Input;
  /** Overrides the reference's texCoord (KHR_texture_transform texCoord). */
  texCoord?: number;
}

/** A material's use of a texture (glTF textureInfo / normalTextureInfo / occlusionTextureInfo). */
export interface WavefrontTextureRefInput {
  /** Index into the scene's `textures`. */
  index: number;
  /** UV set: 0 (`uvs`) or 1 (`uvs1`); default 0. */
  texCoord?: number;
  transform?: WavefrontTextureTransformInput;
  /** normalTexture.scale (default 1); also clearcoatNormalTexture.scale. */
  scale?: number;
  /** occlusionTexture.strength (default 1). */
  strength?: number;
}

export type Vec3Row = [number, number, number];

/** The TextureBinding rows: transform0 = (a, b, tx), transform1 = (c, d, ty). */
export interface TextureTransformRows {
  transform0: Vec3Row;
  transform1: Vec3Row;
}

/** A validated texture reference: which texture, which uv set, the uv transform, scale/strength. */
export interface NormalizedTextureRef {
  texture: number;
  texCoord: 0 | 1;
  transform: TextureTransformRows;
  /** normalTexture.scale or occlusionTexture.strength (1 otherwise). */
  scale: number;
}
