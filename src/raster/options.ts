import { describe, fail, requireFiniteNumber, requireInteger } from '../errors/validate.ts';
import type { WavefrontToneMapping } from '../scene/types.ts';
import type { RasterRendererOptions } from './types.ts';

const knownKeys = new Set([
  'width', 'height', 'camera', 'meshes', 'instances', 'materials', 'textures', 'images', 'lights', 'skinnedMeshes', 'skinnedInstances',
  'environment', 'environmentMap', 'environmentLighting', 'toneMapping', 'exposure', 'msaa', 'shadow', 'canvas', 'format', 'device', 'powerPreference',
]);
const toneMappings: readonly WavefrontToneMapping[] = ['neutral', 'aces', 'linear', 'agx'];

export interface ValidatedRasterOptions {
  width: number;
  height: number;
  toneMapping: WavefrontToneMapping;
  exposure: number;
  msaa: 1 | 4;
  shadow: { light: number | undefined; mapSize: number; bias: number } | null;
}

/** Checks the renderer's own options (the scene is checked by normalizeRasterScene). */
export function validateRasterOptions(options: RasterRendererOptions, maxDimension: number): ValidatedRasterOptions {
  if (typeof options !== 'object' || options === null) fail('INVALID_OPTION', 'options', `expected an options object, got ${describe(options)}`);
  for (const key of Object.keys(options)) if (!knownKeys.has(key)) fail('INVALID_OPTION', key, 'unknown option');
  const width = requireInteger(options.width, 'width', { min: 1, max: maxDimension });
  const height = requireInteger(options.height, 'height', { min: 1, max: maxDimension });
  const toneMapping = options.toneMapping ?? 'neutral';
  if (!toneMappings.includes(toneMapping)) fail('INVALID_OPTION', 'toneMapping', `expected one of ${toneMappings.join(', ')}, got ${describe(toneMapping)}`);
  const exposure = options.exposure === undefined ? 1 : requireFiniteNumber(options.exposure, 'exposure');
  if (!(exposure >= 0)) fail('INVALID_OPTION', 'exposure', `must be >= 0, got ${exposure}`);
  const msaa = options.msaa ?? 4;
  if (msaa !== 1 && msaa !== 4) fail('INVALID_OPTION', 'msaa', `expected 1 or 4, got ${describe(msaa)}`);
  let shadow: ValidatedRasterOptions['shadow'] = { light: undefined, mapSize: 2048, bias: 0.002 };
  if (options.shadow === false) shadow = null;
  else if (options.shadow !== undefined) {
    const s = options.shadow;
    if (typeof s !== 'object' || s === null) fail('INVALID_OPTION', 'shadow', 'expected { light?, mapSize?, bias? } or false');
    shadow = {
      light: s.light === undefined ? undefined : requireInteger(s.light, 'shadow.light', { min: 0, max: (options.lights?.length ?? 0) - 1 }),
      mapSize: s.mapSize === undefined ? 2048 : requireInteger(s.mapSize, 'shadow.mapSize', { min: 16, max: maxDimension }),
      bias: s.bias === undefined ? 0.002 : requireFiniteNumber(s.bias, 'shadow.bias'),
    };
  }
  return { width, height, toneMapping, exposure, msaa, shadow };
}
