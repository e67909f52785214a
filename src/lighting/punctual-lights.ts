import { fail, requireFiniteNumber, requireVec, describe } from '../errors/validate.ts';
import { allocateStructArray, writeStruct } from '../gpu-layout/struct-layout.ts';
import type { WavefrontPunctualLightInput } from '../scene/types.ts';
import { dot, length, normalize, scale, sub, type Vec3 } from './vec3.ts';
import { PUNCTUAL_LIGHT_POINT, PUNCTUAL_LIGHT_SPOT, PUNCTUAL_LIGHT_DIRECTIONAL } from '../gpu-layout/constants.ts';
import { punctualLightLayout } from '../gpu-layout/records.ts';
import { requireKnownKeys } from './known-keys.ts';

export { PUNCTUAL_LIGHT_POINT, PUNCTUAL_LIGHT_SPOT, PUNCTUAL_LIGHT_DIRECTIONAL };
export { punctualLightLayout };

/**
 * KHR_lights_punctual point, spot and directional lights: validation, GPU packing and the CPU
 * reference of their incident radiance. Delta lights are sampled by next-event estimation and never
 * hit by rays, so they have no pdf for MIS.
 */

export type PunctualLightType = 'point' | 'spot' | 'directional';

/** A validated punctual light in world space. */
export interface PunctualLight {
  type: PunctualLightType;
  /** Point and spot. */
  position: Vec3;
  /** Unit direction the light travels in (spot, directional). */
  direction: Vec3;
  /** color x intensity: candela (point, spot) or lux (directional), per channel. */
  intensity: Vec3;
  /** Infinity when unbounded. */
  range: number;
  innerConeAngle: number;
  outerConeAngle: number;
}

const CODE = 'INVALID_LIGHT';

function nonNegativeVec3(value: unknown, field: string): Vec3 {
  const v = requireVec(value, 3, field, CODE);
  v.forEach((x, i) => {
    if (x < 0) fail(CODE, `${field}[${i}]`, `must be >= 0, got ${x}`);
  });
  return v as Vec3;
}

function unitVec3(value: unknown, field: string): Vec3 {
  const v = requireVec(value, 3, field, CODE);
  const l = length(v);
  if (!(l > 0) || !Number.isFinite(l)) fail(CODE, field, 'must be a non-zero vector');
  return normalize(v);
}

/**
 * Validates one KHR_lights_punctual light (glTF 2.0 KHR_lights_punctual: intensity >= 0, range > 0,
 * 0 <= innerConeAngle < outerConeAngle <= pi / 2). Errors are `INVALID_LIGHT` naming the field.
 */
export function validatePunctualLight(input: unknown, field = 'light'): PunctualLight {
  if (typeof input !== 'object' || input === null) fail(CODE, field, `expected an object, got ${describe(input)}`);
  const l = input as WavefrontPunctualLightInput & Record<string, unknown>;
  requireKnownKeys(l, ['type', 'name', 'color', 'intensity', 'range', 'position', 'direction', 'innerConeAngle', 'outerConeAngle'], field, CODE);
  const type = l.type;
  if (type !== 'point' && type !== 'spot' && type !== 'directional') fail(CODE, `${field}.type`, `expected 'point', 'spot' or 'directional', got ${describe(type)}`);
  const color = l.color === undefined ? [1, 1, 1] : nonNegativeVec3(l.color, `${field}.color`);
  const intensity = l.intensity === undefined ? 1 : requireFiniteNumber(l.intensity, `${field}.intensity`, CODE);
  if (intensity < 0) fail(CODE, `${field}.intensity`, `must be >= 0, got ${intensity}`);
  let range = Infinity;
  if (l.range !== undefined && type !== 'directional') {
    range = requireFiniteNumber(l.range, `${field}.range`, CODE);
    if (!(range > 0)) fail(CODE, `${field}.range`, `must be > 0, got ${range}`);
  }
  const position: Vec3 = type === 'directional' ? [0, 0, 0] : (requireVec(l.position, 3, `${field}.position`, CODE) as Vec3);
  const direction: Vec3 = type === 'point' ? [0, 0, -1] : unitVec3(l.direction, `${field}.direction`);
  let innerConeAngle = 0;
  let outerConeAngle = Math.PI / 4;
  if (type === 'spot') {
    if (l.innerConeAngle !== undefined) innerConeAngle = requireFiniteNumber(l.innerConeAngle, `${field}.innerConeAngle`, CODE);
    if (l.outerConeAngle !== undefined) outerConeAngle = requireFiniteNumber(l.outerConeAngle, `${field}.outerConeAngle`, CODE);
    if (!(outerConeAngle > 0 && outerConeAngle <= Math.PI / 2)) fail(CODE, `${field}.outerConeAngle`, `must be in (0, pi/2], got ${outerConeAngle}`);
    if (!(innerConeAngle >= 0 && innerConeAngle < outerConeAngle)) fail(CODE, `${field}.innerConeAngle`, `must be in [0, outerConeAngle), got ${innerConeAngle}`);
  }
  return { type, position, direction, intensity: scale(color, intensity), range, innerConeAngle, outerConeAngle };
}

/** KHR_lights_punctual's spot falloff constants: scale = 1 / max(0.001, cos(inner) - cos(outer)). */
export function spotAngleScaleOffset(light: Pick<PunctualLight, 'innerConeAngle' | 'outerConeAngle'>): { scale: number; offset: number } {
  const cosOuter = Math.cos(light.outerConeAngle);
  const s = 1 / Math.max(0.001, Math.cos(light.innerConeAngle) - cosOuter);
  return { scale: s, offset: -cosOuter * s };
}

export interface PunctualIncident {
  /** Unit direction from the shading point towards the light. */
  wi: Vec3;
  /** Distance to the light (Infinity for directional lights): the shadow ray's length. */
  distance: number;
  /**
   * Incident radiance of the delta light, integrated over its delta: a surface adds
   * f(wo, wi) x incident x |cos theta_i|. intensity / d^2 x range window x spot falloff, or the
   * directional light's illuminance.
   */
  incident: Vec3;
}

/**
 * CPU reference of a punctual light's contribution at `p` (KHR_lights_punctual, "Range Property" and
 * "Inner and Outer Cone Angles"): window = clamp(1 - (d / range)^4, 0, 1), divided by d^2; spot
 * falloff = saturate(dot(direction, -wi) * scale + offset)^2.
 */
export function punctualLightIncident(light: PunctualLight, p: readonly number[]): PunctualIncident {
  if (light.type === 'directional') return { wi: scale(light.direction, -1), distance: Infinity, incident: [...light.intensity] };
  const toLight = sub(light.position, p);
  const d2 = dot(toLight, toLight);
  const distance = Math.sqrt(d2);
  if (!(distance > 0)) return { wi: [0, 0, 1], distance: 0, incident: [0, 0, 0] };
  const wi = scale(toLight, 1 / distance);
  let attenuation = 1 / d2;
  if (Number.isFinite(light.range)) attenuation *= Math.min(1, Math.max(0, 1 - (distance / light.range) ** 4));
  if (light.type === 'spot') {
    const { scale: s, offset } = spotAngleScaleOffset(light);
    const cd = -dot(light.direction, wi);
    const a = Math.min(1, Math.max(0, cd * s + offset));
    attenuation *= a * a;
  }
  return { wi, distance, incident: scale(light.intensity, attenuation) };
}



/** Packs validated punctual lights (at least one zeroed record, as WebGPU bindings cannot be empty). */
export function packPunctualLights(lights: readonly PunctualLight[]): ArrayBuffer {
  const buffer = allocateStructArray(punctualLightLayout, lights.length);
  const view = new DataView(buffer);
  lights.forEach((l, i) => {
    const spot = l.type === 'spot' ? spotAngleScaleOffset(l) : { scale: 0, offset: 1 };
    writeStruct(punctualLightLayout, view, i, {
      position: l.position,
      kind: l.type === 'point' ? PUNCTUAL_LIGHT_POINT : l.type === 'spot' ? PUNCTUAL_LIGHT_SPOT : PUNCTUAL_LIGHT_DIRECTIONAL,
      direction: l.direction,
      invRange: Number.isFinite(l.range) ? 1 / l.range : 0,
      intensity: l.intensity,
      spotScale: spot.scale,
      spotOffset: spot.offset,
    });
  });
  return buffer;
}
