import { describe, fail, requireNumberInRange, requireVec } from '../errors/validate.ts';
import { maxCoordinateMagnitude } from '../scene/limits.ts';
import type { WavefrontCameraInput } from '../scene/types.ts';

export type Vec3 = [number, number, number];

/** A validated camera with its orthonormal basis (right-handed, looking down `forward`). */
export interface WavefrontCamera {
  kind: 'perspective' | 'orthographic';
  position: Vec3;
  target: Vec3;
  up: Vec3;
  fovYDegrees: number;
  forward: Vec3;
  right: Vec3;
  /** Up, orthogonalised against forward. */
  trueUp: Vec3;
  tanHalfFovY: number;
  /** Orthographic: half the height of the view volume. */
  orthographicHalfHeight: number;
}

export const defaultWavefrontCamera: WavefrontCameraInput = { position: [0, 0, 3.9], target: [0, 0, 0], up: [0, 1, 0], fovYDegrees: 39.3 };

const sub = (a: Vec3, b: Vec3): Vec3 => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const cross = (a: Vec3, b: Vec3): Vec3 => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const length = (a: Vec3): number => Math.hypot(a[0], a[1], a[2]);
const scale = (a: Vec3, s: number): Vec3 => [a[0] * s, a[1] * s, a[2] * s];

export function normalizeWavefrontCamera(input: WavefrontCameraInput | undefined, field = 'camera'): WavefrontCamera {
  // Only undefined means "the default camera": null is refused like any other non-object.
  const c = input === undefined ? defaultWavefrontCamera : input;
  if (typeof c !== 'object' || c === null || Array.isArray(c)) fail('INVALID_OPTION', field, `expected a camera object, got ${describe(c)}`);
  for (const key of Object.keys(c)) {
    if (!['type', 'position', 'target', 'up', 'fovYDegrees', 'orthographicHeight'].includes(key)) fail('INVALID_OPTION', `${field}.${key}`, 'unknown camera key');
  }
  const kind = c.type ?? 'perspective';
  if (kind !== 'perspective' && kind !== 'orthographic') fail('INVALID_OPTION', `${field}.type`, `expected "perspective" or "orthographic", got ${JSON.stringify(kind)}`);
  const orthographicHeight = c.orthographicHeight === undefined ? 2 : requireNumberInRange(c.orthographicHeight, `${field}.orthographicHeight`, { min: Number.MIN_VALUE, max: 1e18 });
  const position = requireVec(c.position, 3, `${field}.position`) as Vec3;
  const target = requireVec(c.target, 3, `${field}.target`) as Vec3;
  // Coordinates the renderer supports (scene/limits.ts): beyond them float32 ray arithmetic overflows.
  for (const [name, v] of [['position', position], ['target', target]] as const) {
    v.forEach((x, i) => {
      if (Math.abs(x) > maxCoordinateMagnitude) fail('INVALID_OPTION', `${field}.${name}[${i}]`, `${x} is beyond the supported coordinate range of +-${maxCoordinateMagnitude}`);
    });
  }
  const up = (c.up === undefined ? [0, 1, 0] : requireVec(c.up, 3, `${field}.up`)) as Vec3;
  const fovYDegrees = c.fovYDegrees === undefined ? 45 : requireNumberInRange(c.fovYDegrees, `${field}.fovYDegrees`, { min: 1e-3, max: 179 });
  const toTarget = sub(target, position);
  const dist = length(toTarget);
  if (!(dist > 0)) fail('INVALID_OPTION', `${field}.target`, 'target must differ from position');
  const forward = scale(toTarget, 1 / dist);
  const r = cross(forward, up);
  const rl = length(r);
  if (!(rl > 1e-9 * Math.max(1, length(up)))) fail('INVALID_OPTION', `${field}.up`, 'up must not be parallel to the view direction');
  const right = scale(r, 1 / rl);
  const trueUp = cross(right, forward);
  return { kind, position, target, up, fovYDegrees, forward, right, trueUp, tanHalfFovY: Math.tan((fovYDegrees * Math.PI) / 360), orthographicHalfHeight: orthographicHeight / 2 };
}
