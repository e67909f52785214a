import type { WavefrontMaterialInput, WavefrontSceneDescription } from '../scene/types.ts';
import type { WavefrontLightingOptions, WavefrontSceneLightInput } from './lighting-options.ts';

/** A scene with the renderer's lighting options, as the CLI and the loaders hand it on. */
export type SceneWithLighting = Omit<WavefrontSceneDescription, 'lights'> & Pick<WavefrontLightingOptions, 'environmentMap' | 'environmentLighting'> & { lights?: readonly WavefrontSceneLightInput[] };

function emits(material: WavefrontMaterialInput | number | undefined): boolean {
  if (typeof material !== 'object') return false;
  const strength = material.emissiveStrength ?? 1;
  return strength > 0 && (material.emissiveFactor ?? [0, 0, 0]).some((c) => c > 0);
}

function plural(n: number, word: string): string {
  return `${n} ${word}${n === 1 ? '' : 's'}`;
}

/**
 * What lights the scene, in words (empty: nothing does, and the image is black): its lights by kind,
 * emissive surfaces (materials, meshes and scene objects that emit; KHR_materials_unlit surfaces
 * are emitters), and its environment (a uniform colour, a map or a sky).
 */
export function sceneLightSources(scene: SceneWithLighting): string[] {
  const sources: string[] = [];
  const lights = scene.lights ?? [];
  const punctual = lights.filter((l) => l.type === 'point' || l.type === 'spot' || l.type === 'directional').length;
  if (punctual > 0) sources.push(plural(punctual, 'punctual light'));
  if (lights.length > punctual) sources.push(plural(lights.length - punctual, 'area light'));
  const emissive =
    (scene.materials ?? []).some(emits) ||
    (scene.meshes ?? []).some((m) => emits(m.material) || (m.emission !== undefined && m.emission[3]! > 0 && [0, 1, 2].some((c) => m.emission![c]! > 0))) ||
    (scene.sceneObjects ?? []).some((o) => o.emission !== undefined && o.emission[3]! > 0 && [0, 1, 2].some((c) => o.emission![c]! > 0));
  if (emissive) sources.push('emissive surfaces');
  if (scene.environmentMap !== undefined) sources.push('environment map');
  if (scene.environmentLighting !== undefined) sources.push(`'${scene.environmentLighting.preset ?? 'clear'}' sky`);
  if (scene.environment !== undefined && scene.environment.color.some((c) => c > 0)) sources.push('uniform environment colour');
  return sources;
}
