/** `--env`, `--env-intensity` and `--env-rotation`: the environment map the CLI renders with. */
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import type { EnvironmentMapInput } from '../lighting/environment-map.ts';
import { loadEnvironmentMap } from '../lighting/load-environment-map.ts';
import type { WavefrontSceneDescription } from '../scene/types.ts';
import type { RenderCommand } from './args.ts';
import type { ResourcePolicy } from '../io/resource-policy.ts';

type SceneWithMap = WavefrontSceneDescription & { environmentMap?: EnvironmentMapInput };

/**
 * Replaces the scene's environment with `--env`'s map (a Radiance .hdr or OpenEXR file, read and
 * validated by loadEnvironmentMap: errors are INVALID_ENVIRONMENT naming `--env`), and applies
 * `--env-intensity` / `--env-rotation` (degrees) to whichever map lights the scene; they need one.
 */
export async function applyEnvironmentFlags(
  scene: SceneWithMap,
  command: Pick<RenderCommand, 'env' | 'envIntensity' | 'envRotationDegrees'>,
  resourcePolicy?: ResourcePolicy,
): Promise<SceneWithMap> {
  let map = scene.environmentMap;
  if (command.env !== undefined) map = await loadEnvironmentMap(command.env, { field: '--env', ...(resourcePolicy ? { resourcePolicy } : {}) });
  if (map === undefined) {
    for (const [flag, value] of [['--env-intensity', command.envIntensity], ['--env-rotation', command.envRotationDegrees]] as const) {
      if (value !== undefined) throw new GpuRendererError('INVALID_OPTION', 'needs an environment map: --env, or a scene file whose environment has a map', { field: flag });
    }
    return scene;
  }
  // The map replaces the scene's uniform environment colour.
  const rest: SceneWithMap = { ...scene };
  delete rest.environment;
  return {
    ...rest,
    environmentMap: {
      ...map,
      ...(command.envIntensity !== undefined ? { intensity: command.envIntensity } : {}),
      ...(command.envRotationDegrees !== undefined ? { rotationRadians: (command.envRotationDegrees * Math.PI) / 180 } : {}),
    },
  };
}
