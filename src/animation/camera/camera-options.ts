import { fail, requireFiniteNumber, requireVec } from '../../errors/validate.ts';
import type { Vec3 } from '../model/model-types.ts';
import { CAMERA_VIEW_MODES, type CameraViewMode } from './camera-types.ts';
import { CSS_EASE, validateCubicBezier, type CubicBezier } from './cubic-bezier.ts';

export interface CameraConstraintsInput {
  /** Third-person follow distance range, metres; defaults 1.5 and 12. */
  minDistance?: number;
  maxDistance?: number;
  /** Third-person orbit pitch range, degrees above the horizon; defaults -20 and 70. */
  minPitchDegrees?: number;
  maxPitchDegrees?: number;
  /** Head-look and first-person view limits relative to the heading, degrees; defaults 75 and 60. */
  headYawLimitDegrees?: number;
  headPitchLimitDegrees?: number;
}

/**
 * Camera options of the animated scene: the backward-compatible lagged-follow rig (offset, lagMs,
 * lookAheadMs, cubicBezier), which drives the third-person rig, plus view mode and constraints.
 */
export interface AnimatedCameraOptionsInput {
  viewMode?: CameraViewMode;
  /** Camera position relative to the focus point in world axes; default (0, 1, -4): behind a character facing +Z. */
  offset?: readonly number[];
  /** Follow lag time constant, ms; default 250; 0 follows rigidly. */
  lagMs?: number;
  /** Aim ahead of the focus by velocity x lookAheadMs; default 0. */
  lookAheadMs?: number;
  /** CSS cubic-bezier easing of view-mode transitions; default CSS `ease`. */
  cubicBezier?: readonly number[];
  /** Duration of view-mode transitions, ms; default 0 (cut). */
  transitionMs?: number;
  /** Default 50. */
  fovYDegrees?: number;
  constraints?: CameraConstraintsInput;
  /** Explicit pose for the editor and spectator rigs. */
  position?: readonly number[];
  target?: readonly number[];
  /** Head anchor joint for first-person and head-look; default the joint named "Head" (or ending in ":Head"). */
  headJoint?: string;
  /** Height of the follow focus above the character's ground position; default the rest head height. */
  focusHeight?: number;
}

export interface CameraSettings {
  readonly viewMode: CameraViewMode;
  readonly offset: Vec3;
  readonly lagMs: number;
  readonly lookAheadMs: number;
  readonly cubicBezier: CubicBezier;
  readonly transitionMs: number;
  readonly fovYDegrees: number;
  readonly minDistance: number;
  readonly maxDistance: number;
  readonly minPitch: number;
  readonly maxPitch: number;
  readonly headYawLimit: number;
  readonly headPitchLimit: number;
  readonly position: Vec3 | null;
  readonly target: Vec3 | null;
}

export const DEFAULT_CAMERA_SETTINGS: CameraSettings = {
  viewMode: 'third-person',
  offset: [0, 1, -4],
  lagMs: 250,
  lookAheadMs: 0,
  cubicBezier: CSS_EASE,
  transitionMs: 0,
  fovYDegrees: 50,
  minDistance: 1.5,
  maxDistance: 12,
  minPitch: (-20 * Math.PI) / 180,
  maxPitch: (70 * Math.PI) / 180,
  headYawLimit: (75 * Math.PI) / 180,
  headPitchLimit: (60 * Math.PI) / 180,
  position: null,
  target: null,
};

const RAD = Math.PI / 180;

function nonNegative(value: unknown, field: string): number {
  const n = requireFiniteNumber(value, field);
  if (n < 0) fail('INVALID_OPTION', field, `must be >= 0, got ${n}`);
  return n;
}

export function validateViewMode(value: unknown, field: string): CameraViewMode {
  if (!CAMERA_VIEW_MODES.includes(value as CameraViewMode)) fail('INVALID_OPTION', field, `expected one of ${CAMERA_VIEW_MODES.join(', ')}, got ${JSON.stringify(value)}`);
  return value as CameraViewMode;
}

/** Validates camera options over `base` (defaults or the current settings): a partial update. */
export function validateCameraOptions(input: unknown, field = 'camera', base: CameraSettings = DEFAULT_CAMERA_SETTINGS): CameraSettings {
  if (input === undefined) return base;
  if (typeof input !== 'object' || input === null) fail('INVALID_OPTION', field, 'expected a camera options object');
  const o = input as AnimatedCameraOptionsInput;
  const c = o.constraints ?? {};
  if (typeof c !== 'object' || c === null) fail('INVALID_OPTION', `${field}.constraints`, 'expected an object');
  const settings: CameraSettings = {
    viewMode: o.viewMode === undefined ? base.viewMode : validateViewMode(o.viewMode, `${field}.viewMode`),
    offset: o.offset === undefined ? base.offset : (requireVec(o.offset, 3, `${field}.offset`) as Vec3),
    lagMs: o.lagMs === undefined ? base.lagMs : nonNegative(o.lagMs, `${field}.lagMs`),
    lookAheadMs: o.lookAheadMs === undefined ? base.lookAheadMs : nonNegative(o.lookAheadMs, `${field}.lookAheadMs`),
    cubicBezier: o.cubicBezier === undefined ? base.cubicBezier : validateCubicBezier(o.cubicBezier, `${field}.cubicBezier`),
    transitionMs: o.transitionMs === undefined ? base.transitionMs : nonNegative(o.transitionMs, `${field}.transitionMs`),
    fovYDegrees: o.fovYDegrees === undefined ? base.fovYDegrees : requireFiniteNumber(o.fovYDegrees, `${field}.fovYDegrees`),
    minDistance: c.minDistance === undefined ? base.minDistance : requireFiniteNumber(c.minDistance, `${field}.constraints.minDistance`),
    maxDistance: c.maxDistance === undefined ? base.maxDistance : requireFiniteNumber(c.maxDistance, `${field}.constraints.maxDistance`),
    minPitch: c.minPitchDegrees === undefined ? base.minPitch : requireFiniteNumber(c.minPitchDegrees, `${field}.constraints.minPitchDegrees`) * RAD,
    maxPitch: c.maxPitchDegrees === undefined ? base.maxPitch : requireFiniteNumber(c.maxPitchDegrees, `${field}.constraints.maxPitchDegrees`) * RAD,
    headYawLimit: c.headYawLimitDegrees === undefined ? base.headYawLimit : nonNegative(c.headYawLimitDegrees, `${field}.constraints.headYawLimitDegrees`) * RAD,
    headPitchLimit: c.headPitchLimitDegrees === undefined ? base.headPitchLimit : nonNegative(c.headPitchLimitDegrees, `${field}.constraints.headPitchLimitDegrees`) * RAD,
    position: o.position === undefined ? base.position : (requireVec(o.position, 3, `${field}.position`) as Vec3),
    target: o.target === undefined ? base.target : (requireVec(o.target, 3, `${field}.target`) as Vec3),
  };
  if (!(settings.fovYDegrees > 0 && settings.fovYDegrees < 180)) fail('INVALID_OPTION', `${field}.fovYDegrees`, `must be in (0, 180), got ${settings.fovYDegrees}`);
  if (!(settings.minDistance > 0)) fail('INVALID_OPTION', `${field}.constraints.minDistance`, `must be > 0, got ${settings.minDistance}`);
  if (!(settings.maxDistance >= settings.minDistance)) fail('INVALID_OPTION', `${field}.constraints.maxDistance`, `must be >= minDistance (${settings.minDistance}), got ${settings.maxDistance}`);
  if (!(settings.minPitch >= -Math.PI / 2 && settings.maxPitch <= Math.PI / 2 && settings.minPitch <= settings.maxPitch)) {
    fail('INVALID_OPTION', `${field}.constraints`, 'pitch limits must satisfy -90 <= minPitchDegrees <= maxPitchDegrees <= 90');
  }
  if (Math.hypot(...settings.offset) === 0) fail('INVALID_OPTION', `${field}.offset`, 'offset must not be zero (the camera would sit on its target)');
  return settings;
}
