/**
 * How the CLI lights a scene, and the summary's sentence saying so. A scene with no light of any
 * kind (lights, emissive surfaces, environment) and no `--env` is lit by the built-in neutral
 * studio environment, as model viewers light a bare model; `--env none` renders with no
 * environment at all.
 */
import type { ResourcePolicy } from '../io/resource-policy.ts';
import { createNeutralEnvironment } from '../lighting/neutral-environment.ts';
import { sceneLightSources } from '../lighting/scene-light-sources.ts';
import type { RenderCommand } from './args.ts';
import { applyEnvironmentFlags, ENV_NONE, type SceneWithMap } from './environment-flags.ts';

export const NEUTRAL_LIGHTING_SUMMARY = 'lit by the built-in neutral environment; --env to choose, --env none for none';

type LightingFlags = Pick<RenderCommand, 'env' | 'envIntensity' | 'envRotationDegrees'> & Partial<Pick<RenderCommand, 'negativeTexels'>>;

/**
 * The scene as the CLI renders it (applyEnvironmentFlags, plus the neutral default where nothing
 * lights it), and a sentence for the summary saying what lights it. `--env-intensity` and
 * `--env-rotation` apply to the default environment too.
 */
export async function applyCliLighting<T extends SceneWithMap>(
  scene: T,
  command: LightingFlags,
  note: (text: string) => void = () => {},
  resourcePolicy?: ResourcePolicy,
): Promise<{ scene: T; lighting: string }> {
  const unlit = command.env === undefined && sceneLightSources(scene).length === 0;
  const start = unlit ? { ...scene, environmentMap: createNeutralEnvironment() } : scene;
  const lit = (await applyEnvironmentFlags(start, command, note, resourcePolicy)) as T;
  if (unlit) return { scene: lit, lighting: NEUTRAL_LIGHTING_SUMMARY };
  const sources = sceneLightSources(command.env === undefined ? lit : { ...lit, environmentMap: undefined });
  const own = sources.length > 0 ? `the scene's ${sources.join(', ')}` : '';
  if (command.env === ENV_NONE) {
    return { scene: lit, lighting: own === '' ? 'unlit: --env none and the scene has no light of its own (the image is black)' : `lit by ${own} (--env none: no environment)` };
  }
  if (command.env !== undefined) return { scene: lit, lighting: `lit by --env ${command.env}${own === '' ? '' : ` and ${own}`}` };
  return { scene: lit, lighting: `lit by ${own}` };
}
