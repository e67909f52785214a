import { describe, fail, requireFiniteNumber, requireVec } from '../errors/validate.ts';
import { allocateStructArray, writeStruct } from '../gpu-layout/struct-layout.ts';
import { cross, dot, length, normalize, scale, sub, type Vec3 } from './vec3.ts';
import { AREA_LIGHT_RECTANGLE, AREA_LIGHT_DISK, AREA_LIGHT_SPHERE, AREA_LIGHT_FLAG_TWO_SIDED } from '../gpu-layout/constants.ts';
import { areaLightLayout } from '../gpu-layout/records.ts';
import { requireKnownKeys } from './known-keys.ts';

export { AREA_LIGHT_RECTANGLE, AREA_LIGHT_DISK, AREA_LIGHT_SPHERE, AREA_LIGHT_FLAG_TWO_SIDED };
export { areaLightLayout };

/** Area lights (rectangle, disk, sphere): validation and the GPU record. Inputs: light-types.ts. */

export type AreaLightType = 'rectangle' | 'disk' | 'sphere';

/** A validated area light. */
export interface AreaLight {
  type: AreaLightType;
  center: Vec3;
  /** Rectangle: full edges (orthogonal). Disk and sphere: an orthonormal tangent frame of `normal`. */
  edgeU: Vec3;
  edgeV: Vec3;
  /** Unit front-face normal (rectangle: normalize(cross(edgeU, edgeV))); sphere: +Z, unused. */
  normal: Vec3;
  /** Disk and sphere radius; rectangle 0. */
  radius: number;
  /** Surface area (one side). */
  area: number;
  /** emission x intensity. */
  radiance: Vec3;
  twoSided: boolean;
}

const CODE = 'INVALID_LIGHT';
/** Largest |cos| between a rectangle's edges accepted as orthogonal. */
export const RECTANGLE_ORTHOGONALITY_TOLERANCE = 1e-4;

function positiveVecLength(value: unknown, field: string): Vec3 {
  const v = requireVec(value, 3, field, CODE) as Vec3;
  if (!(length(v) > 0)) fail(CODE, field, 'must be a non-zero vector');
  return v;
}

function tangentFrame(n: Vec3): { t: Vec3; b: Vec3 } {
  const a: Vec3 = Math.abs(n[0]) > 0.9 ? [0, 1, 0] : [1, 0, 0];
  const t = normalize(cross(a, n));
  return { t, b: cross(n, t) };
}

/** Validates one area light; `INVALID_LIGHT` errors name the field (e.g. `lights[3].edgeV`). */
export function validateAreaLight(input: unknown, field = 'light'): AreaLight {
  if (typeof input !== 'object' || input === null) fail(CODE, field, `expected an object, got ${describe(input)}`);
  const l = input as Record<string, unknown>;
  requireKnownKeys(l, ['type', 'name', 'emission', 'intensity', 'twoSided', 'center', 'edgeU', 'edgeV', 'normal', 'radius'], field, CODE);
  const type = l.type;
  if (type !== 'rectangle' && type !== 'disk' && type !== 'sphere') fail(CODE, `${field}.type`, `expected 'rectangle', 'disk' or 'sphere', got ${describe(type)}`);
  const emission = l.emission === undefined ? [1, 1, 1] : requireVec(l.emission, 3, `${field}.emission`, CODE);
  emission.forEach((x, i) => {
    if (x < 0) fail(CODE, `${field}.emission[${i}]`, `must be >= 0, got ${x}`);
  });
  const intensity = l.intensity === undefined ? 1 : requireFiniteNumber(l.intensity, `${field}.intensity`, CODE);
  if (intensity < 0) fail(CODE, `${field}.intensity`, `must be >= 0, got ${intensity}`);
  if (l.twoSided !== undefined && typeof l.twoSided !== 'boolean') fail(CODE, `${field}.twoSided`, `expected a boolean, got ${describe(l.twoSided)}`);
  const twoSided = l.twoSided === true;
  const center = requireVec(l.center, 3, `${field}.center`, CODE) as Vec3;
  const radiance = scale(emission, intensity);
  if (type === 'rectangle') {
    const edgeU = positiveVecLength(l.edgeU, `${field}.edgeU`);
    const edgeV = positiveVecLength(l.edgeV, `${field}.edgeV`);
    const lu = length(edgeU);
    const lv = length(edgeV);
    if (Math.abs(dot(edgeU, edgeV)) > RECTANGLE_ORTHOGONALITY_TOLERANCE * lu * lv) fail(CODE, `${field}.edgeV`, 'must be orthogonal to edgeU');
    const area = lu * lv;
    if (!Number.isFinite(area)) fail(CODE, `${field}.edgeU`, 'rectangle area overflows');
    return { type, center, edgeU, edgeV, normal: normalize(cross(edgeU, edgeV)), radius: 0, area, radiance, twoSided };
  }
  const radius = requireFiniteNumber(l.radius, `${field}.radius`, CODE);
  if (!(radius > 0)) fail(CODE, `${field}.radius`, `must be > 0, got ${radius}`);
  if (type === 'disk') {
    const normal = normalize(positiveVecLength(l.normal, `${field}.normal`));
    const { t, b } = tangentFrame(normal);
    return { type, center, edgeU: t, edgeV: b, normal, radius, area: Math.PI * radius * radius, radiance, twoSided };
  }
  return { type, center, edgeU: [1, 0, 0], edgeV: [0, 1, 0], normal: [0, 0, 1], radius, area: 4 * Math.PI * radius * radius, radiance, twoSided };
}



export function packAreaLights(lights: readonly AreaLight[]): ArrayBuffer {
  const buffer = allocateStructArray(areaLightLayout, lights.length);
  const view = new DataView(buffer);
  lights.forEach((l, i) => {
    const corner = l.type === 'rectangle' ? sub(sub(l.center, scale(l.edgeU, 0.5)), scale(l.edgeV, 0.5)) : l.center;
    writeStruct(areaLightLayout, view, i, {
      corner,
      kind: l.type === 'rectangle' ? AREA_LIGHT_RECTANGLE : l.type === 'disk' ? AREA_LIGHT_DISK : AREA_LIGHT_SPHERE,
      edgeU: l.edgeU,
      radius: l.radius,
      edgeV: l.edgeV,
      flags: l.twoSided ? AREA_LIGHT_FLAG_TWO_SIDED : 0,
      normal: l.normal,
      area: l.area,
      radiance: l.radiance,
    });
  });
  return buffer;
}
