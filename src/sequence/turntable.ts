/**
 * Turntable cameras: a perspective camera orbiting the bounds' centre about +Y (the glTF up axis)
 * at a fixed elevation, far enough that the bounding sphere fits the narrower of the vertical and
 * horizontal fields of view. Frame k of n looks from azimuth 360 k / n degrees, 0 on +Z (the glTF
 * front), increasing counter-clockwise seen from above.
 */
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import type { WavefrontCameraInput } from '../scene/types.ts';

export interface TurntableOptions {
  /** Frames per full orbit. */
  frames: number;
  /** Height of the orbit above the centre, in degrees; default 20. */
  elevationDegrees?: number;
  /** Vertical field of view; default 40 degrees. */
  fovYDegrees?: number;
  /** Distance multiplier over the distance where the bounding sphere just fits; default 1.1. */
  margin?: number;
}

export interface Bounds {
  min: readonly number[];
  max: readonly number[];
}

function invalid(field: string, message: string): never {
  throw new GpuRendererError('INVALID_OPTION', message, { field });
}

/** Validates turntable options (`field` prefixes the error fields). */
export function checkTurntable(options: TurntableOptions, field = 'turntable'): Required<TurntableOptions> {
  const { frames, elevationDegrees = 20, fovYDegrees = 40, margin = 1.1 } = options;
  if (!Number.isInteger(frames) || frames < 1) invalid(`${field}.frames`, `expected an integer >= 1, got ${frames}`);
  if (!Number.isFinite(elevationDegrees) || Math.abs(elevationDegrees) >= 90) invalid(`${field}.elevationDegrees`, `expected degrees in (-90, 90), got ${elevationDegrees}`);
  if (!Number.isFinite(fovYDegrees) || fovYDegrees <= 0 || fovYDegrees >= 180) invalid(`${field}.fovYDegrees`, `expected degrees in (0, 180), got ${fovYDegrees}`);
  if (!Number.isFinite(margin) || margin <= 0) invalid(`${field}.margin`, `expected a number > 0, got ${margin}`);
  return { frames, elevationDegrees, fovYDegrees, margin };
}

/** The camera of frame `frame` of a turntable around `bounds`, for an image of `aspect` = width / height. */
export function turntableCamera(bounds: Bounds | undefined, frame: number, options: TurntableOptions, aspect = 1): WavefrontCameraInput {
  const { frames, elevationDegrees, fovYDegrees, margin } = checkTurntable(options);
  const center = bounds === undefined ? [0, 0, 0] : [0, 1, 2].map((a) => (bounds.min[a]! + bounds.max[a]!) / 2);
  const radius = bounds === undefined ? 1 : Math.hypot(...[0, 1, 2].map((a) => bounds.max[a]! - bounds.min[a]!)) / 2 || 1;
  const halfY = (fovYDegrees * Math.PI) / 360;
  const halfX = Math.atan(Math.tan(halfY) * aspect);
  const distance = (margin * radius) / Math.sin(Math.min(halfX, halfY));
  const azimuth = (2 * Math.PI * (frame % frames)) / frames;
  const elevation = (elevationDegrees * Math.PI) / 180;
  const position = [
    center[0]! + distance * Math.cos(elevation) * Math.sin(azimuth),
    center[1]! + distance * Math.sin(elevation),
    center[2]! + distance * Math.cos(elevation) * Math.cos(azimuth),
  ];
  return { type: 'perspective', position, target: center, up: [0, 1, 0], fovYDegrees };
}
