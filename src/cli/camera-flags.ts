/** `--orbit`, `--camera-position`, `--camera-target` and `--fov`: the camera the CLI renders from. */
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { defaultWavefrontCamera } from '../pathtracer/camera.ts';
import { lookAtCamera, orbitCamera, sceneBounds } from '../scene/camera-framing.ts';
import type { WavefrontSceneDescription } from '../scene/types.ts';
import type { RenderCommand } from './commands.ts';

/**
 * The scene with the camera the flags ask for: an orbit of the bounds' centre (fitted to the image
 * unless a distance is given), or an eye position looking at a target (default the bounds' centre);
 * `--fov` sets the vertical field of view of whichever camera is rendered from.
 */
export function applyCameraFlags<S extends WavefrontSceneDescription>(
  scene: S,
  command: Pick<RenderCommand, 'orbit' | 'cameraPosition' | 'cameraTarget' | 'fovYDegrees' | 'width' | 'height'>,
): S {
  const { orbit, cameraPosition, cameraTarget, fovYDegrees } = command;
  if (orbit !== undefined) {
    const camera = orbitCamera(sceneBounds(scene), orbit, { aspectRatio: command.width / command.height, ...(fovYDegrees !== undefined ? { fovYDegrees } : {}) });
    return { ...scene, camera };
  }
  if (cameraPosition !== undefined) {
    let target = cameraTarget;
    if (target === undefined) {
      const bounds = sceneBounds(scene);
      if (bounds === undefined) throw new GpuRendererError('INVALID_OPTION', 'the scene draws nothing to look at: give --camera-target', { field: '--camera-position' });
      target = bounds.min.map((v, i) => (v + bounds.max[i]!) / 2) as [number, number, number];
    }
    if (target.every((v, i) => v === cameraPosition[i])) throw new GpuRendererError('INVALID_OPTION', 'the camera position and target coincide', { field: '--camera-target' });
    return { ...scene, camera: lookAtCamera(cameraPosition, target, fovYDegrees) };
  }
  if (fovYDegrees === undefined) return scene;
  const camera = scene.camera ?? defaultWavefrontCamera;
  if (camera.type === 'orthographic') throw new GpuRendererError('INVALID_OPTION', 'the camera rendered from is orthographic (it has no field of view)', { field: '--fov' });
  return { ...scene, camera: { ...camera, fovYDegrees } };
}
