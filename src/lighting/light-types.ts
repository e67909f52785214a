/**
 * Input types of the area lights (first-class `lights` entries next to the KHR_lights_punctual
 * lights of src/scene/types.ts). The lead merges `WavefrontAreaLightInput` into the scene's
 * `WavefrontLightInput` union. Radiance = emission x intensity, in the renderer's linear units (the
 * same units as emissive triangles: with KHR_materials_emissive_strength, nits).
 */
import type { Vec3Input } from '../scene/types.ts';

interface WavefrontAreaLightCommon {
  name?: string;
  /** Emitted radiance, linear RGB; default [1, 1, 1]. */
  emission?: Vec3Input;
  /** Multiplies `emission`; default 1. */
  intensity?: number;
  /**
   * Emit from both faces; default false. Rectangle and disk: the front face is the one `normal`
   * (rectangle: cross(edgeU, edgeV)) points out of. Sphere: the outside; two-sided adds the inside.
   */
  twoSided?: boolean;
}

/** A rectangle with orthogonal edges: corners center +- edgeU / 2 +- edgeV / 2. */
export interface WavefrontRectangleLightInput extends WavefrontAreaLightCommon {
  type: 'rectangle';
  center: Vec3Input;
  /** Full edge vectors (not half extents); must be orthogonal (relative |cos| <= 1e-4). */
  edgeU: Vec3Input;
  edgeV: Vec3Input;
}

export interface WavefrontDiskLightInput extends WavefrontAreaLightCommon {
  type: 'disk';
  center: Vec3Input;
  /** Front-face normal (need not be unit length). */
  normal: Vec3Input;
  radius: number;
}

export interface WavefrontSphereLightInput extends WavefrontAreaLightCommon {
  type: 'sphere';
  center: Vec3Input;
  radius: number;
}

export type WavefrontAreaLightInput = WavefrontRectangleLightInput | WavefrontDiskLightInput | WavefrontSphereLightInput;
