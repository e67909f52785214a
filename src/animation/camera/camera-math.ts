import { mat4d } from 'wgpu-matrix';
import type { Vec3 } from '../model/model-types.ts';
import type { CameraTransform } from './camera-types.ts';

/** Unit direction for yaw about +Y (0 = +Z, pi/2 = +X) and pitch above the horizon. */
export function directionFromYawPitch(yaw: number, pitch: number): Vec3 {
  return [Math.sin(yaw) * Math.cos(pitch), Math.sin(pitch), Math.cos(yaw) * Math.cos(pitch)];
}

export function yawPitchFromDirection(d: readonly number[]): { yaw: number; pitch: number; length: number } {
  const length = Math.hypot(d[0], d[1], d[2]);
  if (length === 0) return { yaw: 0, pitch: 0, length: 0 };
  return { yaw: Math.atan2(d[0], d[2]), pitch: Math.asin(Math.min(1, Math.max(-1, d[1] / length))), length };
}

export const add = (a: readonly number[], b: readonly number[]): Vec3 => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
export const sub = (a: readonly number[], b: readonly number[]): Vec3 => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
export const scale = (a: readonly number[], k: number): Vec3 => [a[0] * k, a[1] * k, a[2] * k];
export const lerp3 = (a: readonly number[], b: readonly number[], u: number): Vec3 => [a[0] + (b[0] - a[0]) * u, a[1] + (b[1] - a[1]) * u, a[2] + (b[2] - a[2]) * u];
export const distance = (a: readonly number[], b: readonly number[]): number => Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);

export function clamp(x: number, lo: number, hi: number): number {
  return Math.min(hi, Math.max(lo, x));
}

/** Camera transform looking from `position` at `target` with +Y up (a horizontal fallback when looking straight up or down). */
export function cameraTransform(position: Vec3, target: Vec3, fovYDegrees: number): CameraTransform {
  const d = sub(target, position);
  const length = Math.hypot(d[0], d[1], d[2]);
  const forward: Vec3 = length > 0 ? scale(d, 1 / length) : [0, 0, -1];
  const up: Vec3 = Math.abs(forward[1]) > 1 - 1e-9 ? [0, 0, forward[1] > 0 ? 1 : -1] : [0, 1, 0];
  const aim = length > 0 ? target : add(position, forward);
  return { position, target, up, forward, fovYDegrees, viewMatrix: Array.from(mat4d.lookAt(position, aim, up)) };
}
