/** `loadGltfScene` options: unknown keys and values of the wrong type are INVALID_OPTION naming the key. */
import { fail, describe } from '../../errors/validate.ts';
import type { GltfLoadOptions } from './gltf-scene-reader.ts';

const KEYS = ['camera', 'aspectRatio', 'variant', 'scene', 'animation', 'time', 'signal', 'decoders', 'resourcePolicy', 'defaultLighting'];

export function validateGltfLoadOptions(options: unknown): GltfLoadOptions {
  if (options === undefined) return {};
  if (typeof options !== 'object' || options === null || Array.isArray(options)) fail('INVALID_OPTION', 'options', `expected an options object, got ${describe(options)}`);
  const o = options as Record<string, unknown>;
  for (const key of Object.keys(o)) if (!KEYS.includes(key)) fail('INVALID_OPTION', key, `unknown option (expected one of ${KEYS.join(', ')})`);
  for (const key of ['camera', 'scene'] as const) {
    const v = o[key];
    if (v !== undefined && typeof v !== 'string' && !(typeof v === 'number' && Number.isInteger(v) && v >= 0)) fail('INVALID_OPTION', key, `expected a name or an index, got ${describe(v)}`);
  }
  if (o.aspectRatio !== undefined && !(typeof o.aspectRatio === 'number' && Number.isFinite(o.aspectRatio) && o.aspectRatio > 0)) {
    fail('INVALID_OPTION', 'aspectRatio', `expected a finite number > 0, got ${describe(o.aspectRatio)}`);
  }
  if (o.animation !== undefined && o.animation !== null && typeof o.animation !== 'string' && !(typeof o.animation === 'number' && Number.isInteger(o.animation) && o.animation >= 0)) {
    fail('INVALID_OPTION', 'animation', `expected an animation name, an index or null, got ${describe(o.animation)}`);
  }
  if (o.time !== undefined && !(typeof o.time === 'number' && Number.isFinite(o.time) && o.time >= 0)) fail('INVALID_OPTION', 'time', `expected a finite number of seconds >= 0, got ${describe(o.time)}`);
  if (o.variant !== undefined && typeof o.variant !== 'string') fail('INVALID_OPTION', 'variant', `expected a variant name, got ${describe(o.variant)}`);
  if (o.signal !== undefined && (typeof o.signal !== 'object' || o.signal === null || typeof (o.signal as AbortSignal).throwIfAborted !== 'function')) {
    fail('INVALID_OPTION', 'signal', `expected an AbortSignal, got ${describe(o.signal)}`);
  }
  if (o.decoders !== undefined && (typeof o.decoders !== 'object' || o.decoders === null)) fail('INVALID_OPTION', 'decoders', `expected an object of decoder modules, got ${describe(o.decoders)}`);
  if (o.defaultLighting !== undefined && o.defaultLighting !== 'none' && o.defaultLighting !== 'neutral') fail('INVALID_OPTION', 'defaultLighting', `expected 'none' or 'neutral', got ${describe(o.defaultLighting)}`);
  return o as GltfLoadOptions;
}
