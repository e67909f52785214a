/** Input types of the path tracer's scene description (the public scene format). */

export type Vec2Input = readonly [number, number] | readonly number[];
export type Vec3Input = readonly [number, number, number] | readonly number[];
export type Vec4Input = readonly [number, number, number, number] | readonly number[];

/** glTF 2.0 metallic-roughness material factors (plus KHR_materials_ior / emissive_strength). */
export interface WavefrontMaterialInput {
  /** Linear RGB(A), default [1, 1, 1, 1]. */
  baseColorFactor?: Vec3Input | Vec4Input;
  /** Default 1 (glTF default). */
  metallicFactor?: number;
  /** Default 1 (glTF default). */
  roughnessFactor?: number;
  /** Linear RGB, default [0, 0, 0]. */
  emissiveFactor?: Vec3Input;
  /** KHR_materials_emissive_strength, default 1. */
  emissiveStrength?: number;
  /** KHR_materials_ior, default 1.5. */
  ior?: number;
  /** Emit from both faces; default false (front face = counter-clockwise winding). */
  doubleSided?: boolean;
}

export interface WavefrontMeshInput {
  id?: number | string;
  /** xyz triples. */
  positions: ArrayLike<number>;
  /** Triangle list; omitted means consecutive triples of positions. */
  indices?: ArrayLike<number>;
  /** Per-vertex normals (xyz triples); omitted means the geometric normal. */
  normals?: ArrayLike<number>;
  /** Per-vertex uv pairs. */
  uvs?: ArrayLike<number>;
  material?: WavefrontMaterialInput;
  /** The mirrored package's mesh-level emission: [r, g, b, strength]; overrides material emission. */
  emission?: Vec4Input;
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
  materialKind?: string;
}

export interface WavefrontCameraInput {
  position: Vec3Input;
  target: Vec3Input;
  /** Default [0, 1, 0]. */
  up?: Vec3Input;
  /** Vertical field of view in degrees, default 45. */
  fovYDegrees?: number;
}

export interface WavefrontEnvironmentInput {
  /** Uniform linear radiance. */
  color: Vec3Input;
}

export type WavefrontToneMapping = 'neutral' | 'aces' | 'linear';

/** A whole scene as the CLI's scene JSON carries it. */
export interface WavefrontSceneDescription {
  camera?: WavefrontCameraInput;
  environment?: WavefrontEnvironmentInput;
  meshes?: WavefrontMeshInput[];
  sceneObjects?: WavefrontSceneObjectInput[];
}
