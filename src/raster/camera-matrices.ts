/**
 * View and projection matrices of the raster passes (WebGPU clip space: depth in [0, 1]), with
 * near and far planes fitted to the bounding sphere of what is drawn, and the shadow-casting
 * light's view-projection fitted to a focus sphere.
 */
import { mat4, vec3 } from 'wgpu-matrix';
import { fail, requireFiniteNumber, requireVec } from '../errors/validate.ts';
import type { PunctualLight } from '../lighting/punctual-lights.ts';
import type { WavefrontCameraInput } from '../scene/types.ts';

export interface RasterCamera {
  type: 'perspective' | 'orthographic';
  position: [number, number, number];
  target: [number, number, number];
  up: [number, number, number];
  fovYDegrees: number;
  orthographicHeight: number;
}

export function validateRasterCamera(input: WavefrontCameraInput, field = 'camera'): RasterCamera {
  if (typeof input !== 'object' || input === null) fail('INVALID_OPTION', field, 'expected { position, target, up?, fovYDegrees? }');
  const position = requireVec(input.position, 3, `${field}.position`) as [number, number, number];
  const target = requireVec(input.target, 3, `${field}.target`) as [number, number, number];
  const up = (input.up === undefined ? [0, 1, 0] : requireVec(input.up, 3, `${field}.up`)) as [number, number, number];
  const type = input.type ?? 'perspective';
  if (type !== 'perspective' && type !== 'orthographic') fail('INVALID_OPTION', `${field}.type`, `expected 'perspective' or 'orthographic', got ${String(type)}`);
  const fovYDegrees = input.fovYDegrees === undefined ? 45 : requireFiniteNumber(input.fovYDegrees, `${field}.fovYDegrees`);
  if (!(fovYDegrees > 0 && fovYDegrees < 180)) fail('INVALID_OPTION', `${field}.fovYDegrees`, `must be in (0, 180), got ${fovYDegrees}`);
  const orthographicHeight = input.orthographicHeight === undefined ? 2 : requireFiniteNumber(input.orthographicHeight, `${field}.orthographicHeight`);
  if (!(orthographicHeight > 0)) fail('INVALID_OPTION', `${field}.orthographicHeight`, 'must be > 0');
  const forward = vec3.sub(target, position);
  if (!(vec3.length(forward) > 0)) fail('INVALID_OPTION', `${field}.target`, 'target must differ from position');
  if (!(vec3.length(vec3.cross(forward, up)) > 0)) fail('INVALID_OPTION', `${field}.up`, 'up must not be parallel to the view direction');
  return { type, position, target, up, fovYDegrees, orthographicHeight };
}

/** World -> clip of the camera for a viewport aspect, near/far around the sphere (center, radius). */
export function cameraViewProjection(camera: RasterCamera, aspect: number, center: readonly number[], radius: number): Float32Array {
  const view = mat4.lookAt(camera.position, camera.target, camera.up);
  const forward = vec3.normalize(vec3.sub(camera.target, camera.position));
  const depth = vec3.dot(vec3.sub(center, camera.position), forward);
  const far = Math.max(depth + radius, 1e-3) * 1.01;
  const near = Math.max(far * 1e-5, depth - radius, 1e-3);
  const projection =
    camera.type === 'perspective'
      ? mat4.perspective((camera.fovYDegrees * Math.PI) / 180, aspect, Math.min(near, far * 0.5), far)
      : mat4.ortho((-camera.orthographicHeight * aspect) / 2, (camera.orthographicHeight * aspect) / 2, -camera.orthographicHeight / 2, camera.orthographicHeight / 2, Math.min(0, depth - radius), far);
  return mat4.multiply(projection, view) as Float32Array;
}

/** Unit vector from the target towards the eye: where an orthographic camera's fragments are seen from. */
export function towardsViewer(camera: RasterCamera): Float32Array {
  return vec3.normalize(vec3.sub(camera.position, camera.target)) as Float32Array;
}

/** World -> light clip for the shadow map: an orthographic box around the focus sphere (directional) or the spot cone. */
export function lightViewProjection(light: PunctualLight, center: readonly number[], radius: number): Float32Array {
  const r = Math.max(radius, 1e-3);
  const d = light.direction;
  const up = Math.abs(d[1]) > 0.99 ? [0, 0, 1] : [0, 1, 0];
  if (light.type === 'directional') {
    const eye = vec3.addScaled(center, d, -2 * r);
    const view = mat4.lookAt(eye, center, up);
    return mat4.multiply(mat4.ortho(-r, r, -r, r, 0, 3 * r), view) as Float32Array;
  }
  const view = mat4.lookAt(light.position, vec3.add(light.position, d), up);
  const distance = vec3.distance(light.position, center);
  const far = Math.max(distance + r, 1e-2);
  const near = Math.max(far * 1e-3, distance - r, 1e-3);
  return mat4.multiply(mat4.perspective(2 * light.outerConeAngle, 1, near, far), view) as Float32Array;
}
