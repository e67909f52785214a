/**
 * glTF cameras (section 3.10) -> the renderer's look-at cameras. A camera looks down its node's
 * local -Z with +Y up; position, view direction and up come from the node's world matrix (scale is
 * normalised away). The glTF aspectRatio, znear and zfar are not used: the image aspect ratio is
 * the renderer's width / height, and the path tracer needs no clip planes.
 */
import type { Camera } from '@gltf-transform/core';
import type { WavefrontCameraInput } from '../../scene/types.ts';
import { frameBounds, type SceneBounds } from '../../scene/camera-framing.ts';
import { normalize, transformDirection, type Mat4 } from '../../math/mat4.ts';

/** A camera placed in the scene by a node. */
export interface GltfCameraInfo {
  /** The camera's name, else its node's name, else `camera <index>`. */
  name: string;
  /** Index of the glTF camera (`/cameras/i`). */
  cameraIndex: number;
  /** Index of the node that places it (`/nodes/i`). */
  nodeIndex: number;
  nodeName: string;
  camera: WavefrontCameraInput;
}

export function cameraFromNode(camera: Camera, world: Mat4): WavefrontCameraInput {
  const position = [world[12], world[13], world[14]];
  const forward = normalize(transformDirection(world, [0, 0, -1]));
  const up = normalize(transformDirection(world, [0, 1, 0]));
  const target = [position[0] + forward[0], position[1] + forward[1], position[2] + forward[2]];
  if (camera.getType() === 'orthographic') {
    return { type: 'orthographic', position, target, up, orthographicHeight: 2 * Math.abs(camera.getYMag()) };
  }
  return { type: 'perspective', position, target, up, fovYDegrees: (camera.getYFov() * 180) / Math.PI };
}

/** Axis-aligned world bounds. */
export type GltfBounds = SceneBounds;

/**
 * The camera of an asset without one: `frameBounds` (scene/camera-framing.ts) with its defaults, a
 * raised three-quarter view of the bounds (azimuth 30 degrees from +Z towards +X, elevation 25,
 * 45 degree vertical field of view) at the nearest distance where the whole box is in view.
 */
export function framingCamera(bounds: GltfBounds | undefined, aspectRatio = 1): WavefrontCameraInput {
  return frameBounds(bounds, { aspectRatio });
}
