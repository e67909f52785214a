/** `loadGltfScene` options: unknown keys and values of the wrong type are INVALID_OPTION naming the key. */
import { fail, describe } from '../../errors/validate.ts';
import type { ResourcePolicy } from '../resource-policy.ts';
import type { GltfDecoderModules } from './document-reader.ts';
import type { GltfPoseOptions } from './posing.ts';

export interface GltfLoadOptions extends GltfPoseOptions {
  /**
   * The camera to render from: a glTF camera index (`/cameras/i`) or a name (a camera node's name,
   * else a camera's name). Default: the first camera met in the scene's node order; without one, a
   * camera framing the scene bounds (see `GltfScene.camera`).
   */
  camera?: number | string;
  /** Image width / height the default camera frames the bounds for (assets without a camera); default 1. */
  aspectRatio?: number;
  /** KHR_materials_variants variant name; an unknown name throws INVALID_OPTION (field `variant`). */
  variant?: string;
  /** The glTF scene (index or name); default the asset's default scene, else its first scene. */
  scene?: number | string;
  /** Aborts reading (file reads and fetches) and loading between stages. */
  signal?: AbortSignal;
  /** Decoder modules for KHR_draco_mesh_compression / EXT_meshopt_compression (loaded on demand in Node). */
  decoders?: GltfDecoderModules;
  /**
   * What the asset may read and how much it may decode (src/io/resource-policy.ts): by default
   * references stay in the asset's folder, no other origin is fetched, 2 GiB are decoded at most.
   */
  resourcePolicy?: ResourcePolicy;
  /**
   * What lights an asset with no light of its own (no KHR_lights_punctual light, no emissive
   * material): 'none' (default: nothing, the image is black) or 'neutral', the built-in neutral
   * studio environment (`createNeutralEnvironment()`), returned as the scene's `environmentMap`.
   */
  defaultLighting?: 'none' | 'neutral';
}

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
