/**
 * Input types of the renderer's scene description (the public scene format, shared by the path
 * tracer, the scene JSON files, the glTF loader and the raster renderer).
 *
 * A scene is a set of meshes (indexed vertex streams), optional instances placing meshes with
 * transforms, materials (glTF 2.0 metallic-roughness plus KHR extension factors and texture
 * references), textures (an RGBA8 image plus sampler state), a camera, an environment and lights.
 * Without `instances` every mesh is drawn once, in world space.
 */

import type { MaterialExtensionInputs } from '../materials/extensions/index.ts';
import type { Vec2Input, WavefrontTextureRefInput, WavefrontTextureTransformInput } from './texture-refs.ts';

export type { Vec2Input, WavefrontTextureRefInput, WavefrontTextureTransformInput };

export type Vec3Input = readonly [number, number, number] | readonly number[];
export type Vec4Input = readonly [number, number, number, number] | readonly number[];

export type WavefrontWrapMode = 'repeat' | 'clamp-to-edge' | 'mirrored-repeat';
export type WavefrontMagFilter = 'nearest' | 'linear';
export type WavefrontMinFilter =
  | 'nearest'
  | 'linear'
  | 'nearest-mipmap-nearest'
  | 'linear-mipmap-nearest'
  | 'nearest-mipmap-linear'
  | 'linear-mipmap-linear';

/** glTF sampler state (section 5.26), named instead of GL enums. */
export interface WavefrontSamplerInput {
  /** Default 'repeat'. */
  wrapS?: WavefrontWrapMode;
  /** Default 'repeat'. */
  wrapT?: WavefrontWrapMode;
  /** Default 'linear'. */
  magFilter?: WavefrontMagFilter;
  /** Default 'linear-mipmap-linear'. */
  minFilter?: WavefrontMinFilter;
}

/**
 * A decoded image: RGBA8, row-major, top row first (uv (0, 0) is the top-left corner, as in glTF).
 * Colour-space decoding (sRGB or linear) follows the material slot that uses it, as glTF specifies.
 */
export interface WavefrontImageInput {
  width: number;
  height: number;
  data: Uint8Array | Uint8ClampedArray;
  /**
   * Mip levels 1, 2, ... as a file stores them (a KTX2 file's mip chain), each of WebGPU's size for
   * its level (max(1, floor(size / 2^k))), RGBA8 in the same encoding as `data`. Where a sampler
   * reads mipmaps they are used as they are; levels below the last one given are filtered from
   * `data`. Default: every level filtered from `data`.
   */
  mipLevels?: readonly WavefrontImageLevel[];
}

/** One stored mip level of an image. */
export interface WavefrontImageLevel {
  width: number;
  height: number;
  data: Uint8Array | Uint8ClampedArray;
}

export interface WavefrontTextureInput {
  name?: string;
  /** The image itself, or an index into the scene's `images` (shared by several textures). */
  image: WavefrontImageInput | number;
  sampler?: WavefrontSamplerInput;
}

export type WavefrontAlphaMode = 'OPAQUE' | 'MASK' | 'BLEND';

/**
 * glTF 2.0 metallic-roughness material factors and textures, with the KHR material extensions'
 * factors and textures flattened under their glTF names (MaterialExtensionInputs: one key per
 * factor and texture of each registry entry in materials/extensions/, e.g. sheenColorFactor).
 */
export interface WavefrontMaterialInput extends MaterialExtensionInputs {
  name?: string;
  /** Linear RGB(A), default [1, 1, 1, 1]. */
  baseColorFactor?: Vec3Input | Vec4Input;
  baseColorTexture?: WavefrontTextureRefInput;
  /** Default 1 (glTF default). */
  metallicFactor?: number;
  /** Default 1 (glTF default). */
  roughnessFactor?: number;
  /** B channel metalness, G channel roughness (glTF 2.0 section 3.9.2). */
  metallicRoughnessTexture?: WavefrontTextureRefInput;
  /** Tangent-space normal map; `scale` scales its xy. */
  normalTexture?: WavefrontTextureRefInput;
  /** Loaded and kept for raster renderers; the path tracer computes occlusion itself. */
  occlusionTexture?: WavefrontTextureRefInput;
  /** Linear RGB, default [0, 0, 0]. */
  emissiveFactor?: Vec3Input;
  emissiveTexture?: WavefrontTextureRefInput;
  /** KHR_materials_emissive_strength, default 1. */
  emissiveStrength?: number;
  /** KHR_materials_ior, default 1.5. */
  ior?: number;
  /** Emit and reflect on both faces; default false (front face = counter-clockwise winding). */
  doubleSided?: boolean;
  /** Default 'OPAQUE'. */
  alphaMode?: WavefrontAlphaMode;
  /** MASK threshold, default 0.5. */
  alphaCutoff?: number;
}

export interface WavefrontMeshInput {
  id?: number | string;
  /** xyz triples. */
  positions: ArrayLike<number>;
  /** Triangle list; omitted means consecutive triples of positions. */
  indices?: ArrayLike<number>;
  /** Per-vertex normals (xyz triples); omitted means the geometric normal (flat shading). */
  normals?: ArrayLike<number>;
  /** Per-vertex tangents, xyzw (w = +-1: bitangent sign, glTF TANGENT). */
  tangents?: ArrayLike<number>;
  /** Per-vertex uv pairs, set 0 (glTF TEXCOORD_0). */
  uvs?: ArrayLike<number>;
  /** Per-vertex uv pairs, set 1 (glTF TEXCOORD_1). */
  uvs1?: ArrayLike<number>;
  /** Per-vertex linear colours (glTF COLOR_0): rgb triples or rgba quadruples; they multiply base colour. */
  colors?: ArrayLike<number>;
  /** The mesh's material, inline or as an index into the scene's `materials`. */
  material?: WavefrontMaterialInput | number;
  /** Mesh-level emission [r, g, b, strength], kept so hosts written for the 0.2 API work; overrides material emission. */
  emission?: Vec4Input;
}

/** One placement of a mesh: a shared mesh stays one set of vertex streams, however often placed. */
export interface WavefrontInstanceInput {
  id?: number | string;
  /** Index into the scene's `meshes`. */
  mesh: number;
  /** Object-to-world 4x4 matrix, column-major (glTF); default identity. Must be affine and invertible. */
  transform?: ArrayLike<number>;
  /** Index into the scene's `materials`, replacing the mesh's material (e.g. a KHR_materials_variants mapping). */
  material?: number;
}

export interface WavefrontSceneObjectInput {
  type: 'sphere' | 'box';
  /** Sphere centre. */
  center?: Vec3Input;
  radius?: number;
  /** Box corners (axis-aligned). */
  min?: Vec3Input;
  max?: Vec3Input;
  /** Linear base colour, default [0.8, 0.8, 0.8]. */
  color?: Vec3Input;
  /** [r, g, b, strength]. */
  emission?: Vec4Input;
  roughness?: number;
  metallic?: number;
  ior?: number;
  /**
   * The debug material kind, checked against the fields: 'diffuse' (metallic 0), 'metal' (metallic
   * 1, the default metallic), 'emissive' (needs emission > 0). See scene-object.ts.
   */
  materialKind?: 'diffuse' | 'metal' | 'emissive';
}

export interface WavefrontCameraInput {
  /** Default 'perspective'. */
  type?: 'perspective' | 'orthographic';
  position: Vec3Input;
  target: Vec3Input;
  /** Default [0, 1, 0]. */
  up?: Vec3Input;
  /** Perspective: vertical field of view in degrees, default 45. */
  fovYDegrees?: number;
  /** Orthographic: height of the view volume in scene units (glTF 2 * ymag); default 2. */
  orthographicHeight?: number;
}

export interface WavefrontEnvironmentInput {
  /** Uniform linear radiance. */
  color: Vec3Input;
}

/** KHR_lights_punctual light in world space (glTF 2.0 KHR_lights_punctual; units as specified there). */
export interface WavefrontPunctualLightInput {
  type: 'point' | 'spot' | 'directional';
  name?: string;
  /** Linear RGB, default [1, 1, 1]. */
  color?: Vec3Input;
  /** Candela for point and spot lights, lux for directional lights; default 1. */
  intensity?: number;
  /** Distance beyond which a point or spot light has no effect; default infinite. */
  range?: number;
  /** World position (point, spot). */
  position?: Vec3Input;
  /** World direction the light travels in (spot, directional): the node's -Z axis in glTF. */
  direction?: Vec3Input;
  /** Spot cone angles in radians; defaults 0 and pi / 4. */
  innerConeAngle?: number;
  outerConeAngle?: number;
}

export type WavefrontLightInput = WavefrontPunctualLightInput;

export type WavefrontToneMapping = 'neutral' | 'aces' | 'linear' | 'agx';

/** A whole scene: what a scene JSON file carries and what the glTF loader returns. */
export interface WavefrontSceneDescription {
  camera?: WavefrontCameraInput;
  environment?: WavefrontEnvironmentInput;
  meshes?: WavefrontMeshInput[];
  instances?: WavefrontInstanceInput[];
  materials?: WavefrontMaterialInput[];
  textures?: WavefrontTextureInput[];
  images?: WavefrontImageInput[];
  sceneObjects?: WavefrontSceneObjectInput[];
  lights?: WavefrontLightInput[];
}
