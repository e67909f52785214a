import type { Vec3 } from '../model/model-types.ts';
import { add, cameraTransform, clamp, directionFromYawPitch, scale, sub, yawPitchFromDirection } from './camera-math.ts';
import type { CameraControlInput, CameraTransform } from './camera-types.ts';

/** Pitch limit of the free rigs: just short of straight up or down. */
export const FREE_PITCH_LIMIT = (89 * Math.PI) / 180;
const EDITOR_MIN_DISTANCE = 0.05;
const EDITOR_MAX_DISTANCE = 1e4;

/** Orbit rig state: the camera sits at pivot + direction(yaw, pitch) x distance, looking at the pivot. */
export interface OrbitState {
  pivot: Vec3;
  yaw: number;
  pitch: number;
  distance: number;
}

/** Free-fly rig state: position and look direction. */
export interface FlyState {
  position: Vec3;
  yaw: number;
  pitch: number;
}

/** Angles of a camera relative to the character heading (first-person view, head-look). */
export interface LookState {
  yaw: number;
  pitch: number;
}

export function orbitFromPose(position: Vec3, target: Vec3): OrbitState {
  const { yaw, pitch, length } = yawPitchFromDirection(sub(position, target));
  return { pivot: target, yaw, pitch: clamp(pitch, -FREE_PITCH_LIMIT, FREE_PITCH_LIMIT), distance: clamp(length, EDITOR_MIN_DISTANCE, EDITOR_MAX_DISTANCE) };
}

export function flyFromPose(position: Vec3, target: Vec3): FlyState {
  const { yaw, pitch } = yawPitchFromDirection(sub(target, position));
  return { position, yaw, pitch: clamp(pitch, -FREE_PITCH_LIMIT, FREE_PITCH_LIMIT) };
}

export function orbitPosition(state: OrbitState): Vec3 {
  return add(state.pivot, scale(directionFromYawPitch(state.yaw, state.pitch), state.distance));
}

/** Right and up axes of a view looking along `forward` with +Y up. */
function viewAxes(forward: Vec3): { right: Vec3; up: Vec3 } {
  const r: Vec3 = [-forward[2], 0, forward[0]]; // forward x (0, 1, 0)
  const length = Math.hypot(r[0], r[2]) || 1;
  const right = scale(r, 1 / length);
  const up: Vec3 = [right[1] * forward[2] - right[2] * forward[1], right[2] * forward[0] - right[0] * forward[2], right[0] * forward[1] - right[1] * forward[0]];
  return { right, up };
}

/** Editor rig (orbit / pan / zoom about a pivot). */
export function editorTransform(state: OrbitState, fovYDegrees: number): CameraTransform {
  return cameraTransform(orbitPosition(state), state.pivot, fovYDegrees);
}

export function applyEditorControl(state: OrbitState, control: CameraControlInput): OrbitState {
  const orbit = control.orbit ?? control.look ?? [0, 0];
  let { yaw, pitch, distance, pivot } = state;
  yaw += orbit[0];
  pitch = clamp(pitch + orbit[1], -FREE_PITCH_LIMIT, FREE_PITCH_LIMIT);
  distance = clamp(distance - (control.zoom ?? 0), EDITOR_MIN_DISTANCE, EDITOR_MAX_DISTANCE);
  if (control.pan !== undefined) {
    const { right, up } = viewAxes(scale(directionFromYawPitch(yaw, pitch), -1));
    pivot = add(pivot, add(scale(right, control.pan[0]), scale(up, control.pan[1])));
  }
  if (control.move !== undefined) {
    const forward = scale(directionFromYawPitch(yaw, pitch), -1);
    const { right } = viewAxes(forward);
    pivot = add(pivot, add(add(scale(forward, control.move[0]), scale(right, control.move[1])), [0, control.move[2], 0]));
  }
  return { pivot, yaw, pitch, distance };
}

/** Spectator rig (free fly). */
export function spectatorTransform(state: FlyState, fovYDegrees: number): CameraTransform {
  return cameraTransform(state.position, add(state.position, directionFromYawPitch(state.yaw, state.pitch)), fovYDegrees);
}

export function applySpectatorControl(state: FlyState, control: CameraControlInput): FlyState {
  const look = control.look ?? control.orbit ?? [0, 0];
  const yaw = state.yaw + look[0];
  const pitch = clamp(state.pitch + look[1], -FREE_PITCH_LIMIT, FREE_PITCH_LIMIT);
  const forward = directionFromYawPitch(yaw, pitch);
  const { right } = viewAxes(forward);
  let position = state.position;
  const move = control.move ?? [0, 0, 0];
  position = add(position, add(add(scale(forward, move[0] + (control.zoom ?? 0)), scale(right, move[1])), [0, move[2], 0]));
  if (control.pan !== undefined) position = add(position, add(scale(right, control.pan[0]), [0, control.pan[1], 0]));
  return { position, yaw, pitch };
}

export interface ThirdPersonLimits {
  minDistance: number;
  maxDistance: number;
  minPitch: number;
  maxPitch: number;
}

/** Third-person orbit angles and distance, with the distance clamped to [minDistance, maxDistance]. */
export function constrainThirdPerson(state: { yaw: number; pitch: number; distance: number }, limits: ThirdPersonLimits): { yaw: number; pitch: number; distance: number } {
  return { yaw: state.yaw, pitch: clamp(state.pitch, limits.minPitch, limits.maxPitch), distance: clamp(state.distance, limits.minDistance, limits.maxDistance) };
}

export function applyThirdPersonControl(state: { yaw: number; pitch: number; distance: number }, control: CameraControlInput, limits: ThirdPersonLimits): { yaw: number; pitch: number; distance: number } {
  const orbit = control.orbit ?? [0, 0];
  return constrainThirdPerson({ yaw: state.yaw + orbit[0], pitch: state.pitch + orbit[1], distance: state.distance - (control.zoom ?? 0) }, limits);
}

/** Look angles relative to the heading, clamped to the head limits (first-person view and head-look). */
export function applyLookControl(state: LookState, delta: readonly [number, number], yawLimit: number, pitchLimit: number): LookState {
  return { yaw: clamp(state.yaw + delta[0], -yawLimit, yawLimit), pitch: clamp(state.pitch + delta[1], -pitchLimit, pitchLimit) };
}
