/**
 * `--env`, `--env-intensity`, `--env-rotation` and `--negative-texels`: the environment map the CLI
 * renders with (`--env none`: no environment at all).
 */
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { readByteSource, resolveResourcePolicy, type ResourcePolicy } from '../io/resource-policy.ts';
import type { EnvironmentMapInput } from '../lighting/environment-map.ts';
import type { EnvironmentLightingInput } from '../lighting/environment-lighting.ts';
import { loadEnvironmentMap, type EnvironmentMapSource, type NegativeTexelReport } from '../lighting/load-environment-map.ts';
import type { WavefrontSceneDescription } from '../scene/types.ts';
import type { RenderCommand } from './args.ts';

export type SceneWithMap = WavefrontSceneDescription & { environmentMap?: EnvironmentMapInput; environmentLighting?: EnvironmentLightingInput };

/** `--env none`: render with no environment, not even the scene's own or the built-in default. */
export const ENV_NONE = 'none';

/** What zeroing negative texels changed, as the CLI reports it (nothing when nothing changed). */
export function negativeTexelNote(field: string, report: NegativeTexelReport): string | undefined {
  if (report.channels === 0) return undefined;
  const percent = 100 * report.addedEnergyFraction;
  return `${field}: ${report.channels} negative channel values (lossy EXR ringing) set to 0, adding ${percent.toPrecision(2)} % to the map's energy (--negative-texels error refuses such maps)`;
}

/** The scene without any environment (colour, map or sky). */
function withoutEnvironment(scene: SceneWithMap): SceneWithMap {
  const rest: SceneWithMap = { ...scene };
  delete rest.environment;
  delete rest.environmentMap;
  delete rest.environmentLighting;
  return rest;
}

/**
 * A `.js` / `.mjs` module whose default export is a `data:` URL string, as the HDRIs of
 * @pmndrs/assets are shipped (`export default 'data:application/exr;base64,...'`): read as text,
 * never run. Anything else is a map file read as it is.
 */
async function environmentSource(path: string, resourcePolicy: ResourcePolicy | undefined): Promise<EnvironmentMapSource> {
  if (!/\.m?js$/i.test(path)) return path;
  // Read as any source is: a regular file within the resource limits (never a pipe or device).
  const site = { code: 'INVALID_ENVIRONMENT', field: '--env' } as const;
  const { bytes } = await readByteSource(path, await resolveResourcePolicy(resourcePolicy), site);
  const text = new TextDecoder().decode(bytes);
  const match = /^\s*export\s+default\s+(['"])(data:[^'"\s]+)\1\s*;?\s*$/.exec(text);
  if (match === null) throw new GpuRendererError('INVALID_ENVIRONMENT', 'a .js environment map must be a module whose only statement is `export default "data:..."`', { field: '--env' });
  return new URL(match[2]!);
}

/**
 * Replaces the scene's environment with `--env`'s map (a Radiance .hdr or OpenEXR file, or a
 * module exporting one as a data: URL; read and validated by loadEnvironmentMap: errors are
 * INVALID_ENVIRONMENT naming `--env`; `--env none` removes the scene's environment), and applies `--env-intensity` / `--env-rotation` (degrees)
 * to whichever map lights the scene; they need one. `note` receives what `--negative-texels zero`
 * changed; `resourcePolicy` bounds the read (the CLI's: see render-command.ts).
 */
export async function applyEnvironmentFlags(
  scene: SceneWithMap,
  command: Pick<RenderCommand, 'env' | 'envIntensity' | 'envRotationDegrees'> & Partial<Pick<RenderCommand, 'negativeTexels'>>,
  note: (text: string) => void = () => {},
  resourcePolicy?: ResourcePolicy,
): Promise<SceneWithMap> {
  let map = scene.environmentMap;
  if (command.env === ENV_NONE) {
    scene = withoutEnvironment(scene);
    map = undefined;
  } else if (command.env !== undefined) {
    const negativeTexels = command.negativeTexels ?? 'zero';
    map = await loadEnvironmentMap(await environmentSource(command.env, resourcePolicy), {
      field: '--env',
      negativeTexels,
      ...(resourcePolicy ? { resourcePolicy } : {}),
      onNegativeTexels: (report) => {
        const text = negativeTexelNote('--env', report);
        if (text !== undefined) note(text);
      },
    });
  }
  if (map === undefined) {
    for (const [flag, value] of [['--env-intensity', command.envIntensity], ['--env-rotation', command.envRotationDegrees]] as const) {
      if (value !== undefined) throw new GpuRendererError('INVALID_OPTION', 'needs an environment map: --env, or a scene file whose environment has a map', { field: flag });
    }
    return scene;
  }
  // The map replaces the scene's uniform environment colour.
  return {
    ...withoutEnvironment(scene),
    environmentMap: {
      ...map,
      ...(command.envIntensity !== undefined ? { intensity: command.envIntensity } : {}),
      ...(command.envRotationDegrees !== undefined ? { rotationRadians: (command.envRotationDegrees * Math.PI) / 180 } : {}),
    },
  };
}
