/**
 * Turntable cameras: frame k of n looks at the bounds' centre from azimuth 360 k / n degrees about
 * +Y (0 on +Z, the glTF front, towards +X) at a fixed elevation, at the one distance where the
 * bounds' bounding sphere fits the image in every direction (`frameBounds` with `fit: 'sphere'`,
 * the camera framing the glTF loader and the CLI's --orbit use).
 */
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { frameBounds, type SceneBounds } from '../scene/camera-framing.ts';
import type { WavefrontCameraInput } from '../scene/types.ts';

export interface TurntableOptions {
  /** Frames per full orbit. */
  frames: number;
  /** Height of the orbit above the centre, in degrees; default 20. */
  elevationDegrees?: number;
  /** Vertical field of view; default 45 degrees. */
  fovYDegrees?: number;
  /** Share of the half image kept free around the bounding sphere, in [0, 0.5]; default 0.05. */
  margin?: number;
}

function invalid(field: string, message: string): never {
  throw new GpuRendererError('INVALID_OPTION', message, { field });
}

/** Validates turntable options (`field` prefixes the error fields). */
export function checkTurntable(options: TurntableOptions, field = 'turntable'): Required<TurntableOptions> {
  const { frames, elevationDegrees = 20, fovYDegrees = 45, margin = 0.05 } = options;
  if (!Number.isInteger(frames) || frames < 1) invalid(`${field}.frames`, `expected an integer >= 1, got ${frames}`);
  if (!Number.isFinite(elevationDegrees) || Math.abs(elevationDegrees) >= 90) invalid(`${field}.elevationDegrees`, `expected degrees in (-90, 90), got ${elevationDegrees}`);
  if (!Number.isFinite(fovYDegrees) || fovYDegrees <= 0 || fovYDegrees >= 180) invalid(`${field}.fovYDegrees`, `expected degrees in (0, 180), got ${fovYDegrees}`);
  if (!Number.isFinite(margin) || margin < 0 || margin > 0.5) invalid(`${field}.margin`, `expected a share in [0, 0.5], got ${margin}`);
  return { frames, elevationDegrees, fovYDegrees, margin };
}

/** The camera of frame `frame` of a turntable around `bounds`, for an image of `aspect` = width / height. */
export function turntableCamera(bounds: SceneBounds | undefined, frame: number, options: TurntableOptions, aspect = 1): WavefrontCameraInput {
  const { frames, elevationDegrees, fovYDegrees, margin } = checkTurntable(options);
  return frameBounds(bounds, { azimuthDegrees: (360 * (frame % frames)) / frames, elevationDegrees, fovYDegrees, aspectRatio: aspect, margin, fit: 'sphere' });
}
