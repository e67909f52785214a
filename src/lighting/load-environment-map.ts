import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { describe } from '../errors/validate.ts';
import { budgetOf, derivePolicy, readByteSource, resolveResourcePolicy, type ByteSource, type ResourcePolicy } from '../io/resource-policy.ts';
import { decodeOpenExr, isOpenExr, type ExrLoaderConstructor } from '../io/images/openexr.ts';
import { decodeRadianceHdr, isRadianceHdr } from '../io/images/radiance-hdr.ts';
import { MAX_ENVIRONMENT_MAP_DIMENSION, validateEnvironmentMap, type EnvironmentMap } from './environment-map.ts';

/** Where an environment map comes from: a file path (Node), a URL (fetched), or the file's bytes. */
export type EnvironmentMapSource = ByteSource;

export interface LoadEnvironmentMapOptions {
  /** Radiance multiplier, default 1. */
  intensity?: number;
  /** Rotation about +Y in radians, default 0. */
  rotationRadians?: number;
  /** three.js's EXRLoader class, for bundled browser apps (see src/io/images/openexr.ts); Node imports it itself. */
  EXRLoader?: ExrLoaderConstructor;
  /** Name used in error fields, default 'source'. */
  field?: string;
  /**
   * Channel values below zero, which lossy OpenEXR compressions (DWAA/DWAB) leave as ringing beside
   * bright texels: `'error'` (default) refuses the map, naming the first one; `'zero'` sets them to
   * 0 (which adds energy) and reports how many and how much through `onNegativeTexels`.
   */
  negativeTexels?: 'error' | 'zero';
  /** With `negativeTexels: 'zero'`: called once with what was changed (also when nothing was). */
  onNegativeTexels?: (report: NegativeTexelReport) => void;
  /** Ends reading or fetching the file; the load rejects with the signal's reason. */
  signal?: AbortSignal;
  /**
   * Limits of the read and the decode (src/io/resource-policy.ts): the file must be a regular file
   * (inside `root` when given), within `maxResourceBytes`, fetched within `fetchTimeoutMs`; its
   * texels count against `maxDecodedBytes`.
   */
  resourcePolicy?: ResourcePolicy;
}

const OPTION_KEYS = ['intensity', 'rotationRadians', 'EXRLoader', 'field', 'negativeTexels', 'onNegativeTexels', 'signal', 'resourcePolicy'];

/** What `negativeTexels: 'zero'` changed. */
export interface NegativeTexelReport {
  /** Channel values (R, G or B) that were below zero. */
  channels: number;
  /** Their magnitude summed, over the sum of the map's non-negative channel values. */
  addedEnergyFraction: number;
}

/** Sets negative colour channels to 0 in place; returns what changed. */
function zeroNegativeChannels(data: Float32Array): NegativeTexelReport {
  let channels = 0;
  let removed = 0;
  let kept = 0;
  for (let i = 0; i < data.length; i++) {
    if (i % 4 === 3) continue;
    const v = data[i]!;
    if (v < 0) {
      channels++;
      removed -= v;
      data[i] = 0;
    } else if (Number.isFinite(v)) kept += v;
  }
  return { channels, addedEnergyFraction: kept > 0 ? removed / kept : 0 };
}

/**
 * Loads a Radiance .hdr or OpenEXR environment map (format told by the file's signature) from a
 * path, URL or bytes, and validates it as an `environmentMap` (equirectangular, top row = +Y).
 * Unreadable, truncated or unknown files, and texels that are negative or not finite, raise
 * `INVALID_ENVIRONMENT` errors.
 */
export async function loadEnvironmentMap(source: EnvironmentMapSource, options: LoadEnvironmentMapOptions = {}): Promise<EnvironmentMap> {
  if (typeof options !== 'object' || options === null) throw new GpuRendererError('INVALID_OPTION', `expected an options object, got ${describe(options)}`, { field: 'options' });
  for (const key of Object.keys(options)) {
    if (!OPTION_KEYS.includes(key)) throw new GpuRendererError('INVALID_OPTION', `unknown option (expected one of ${OPTION_KEYS.join(', ')})`, { field: key });
  }
  if (options.field !== undefined && typeof options.field !== 'string') throw new GpuRendererError('INVALID_OPTION', `expected a field name, got ${describe(options.field)}`, { field: 'field' });
  const field = options.field ?? 'source';
  if (!(typeof source === 'string' || source instanceof URL || source instanceof ArrayBuffer || source instanceof Uint8Array)) {
    throw new GpuRendererError('INVALID_ENVIRONMENT', 'expected a path, a URL, an ArrayBuffer or a Uint8Array', { field });
  }
  const negative = options.negativeTexels ?? 'error';
  if (negative !== 'error' && negative !== 'zero') throw new GpuRendererError('INVALID_OPTION', `expected 'error' or 'zero', got ${String(negative)}`, { field: 'negativeTexels' });
  if (options.onNegativeTexels !== undefined && typeof options.onNegativeTexels !== 'function') {
    throw new GpuRendererError('INVALID_OPTION', `expected a function, got ${describe(options.onNegativeTexels)}`, { field: 'onNegativeTexels' });
  }
  if (options.EXRLoader !== undefined && typeof options.EXRLoader !== 'function') throw new GpuRendererError('INVALID_OPTION', `expected three.js's EXRLoader class, got ${describe(options.EXRLoader)}`, { field: 'EXRLoader' });
  const resourcePolicy = await resolveResourcePolicy(options.resourcePolicy);
  const budget = budgetOf(resourcePolicy);
  const { signal } = options;
  signal?.throwIfAborted();
  const site = { code: 'INVALID_ENVIRONMENT', field } as const;
  const { bytes } = await readByteSource(source, derivePolicy(resourcePolicy, { budget }), site, signal);
  let image;
  const maxImageDimension = MAX_ENVIRONMENT_MAP_DIMENSION;
  if (isRadianceHdr(bytes)) image = decodeRadianceHdr(bytes, { field, code: 'INVALID_ENVIRONMENT', budget, maxImageDimension, limitName: 'map side' });
  else if (isOpenExr(bytes)) image = await decodeOpenExr(bytes, field, options.EXRLoader, { budget, maxImageDimension, decodeTimeoutMs: resourcePolicy.decodeTimeoutMs, ...(signal ? { signal } : {}) });
  else throw new GpuRendererError('INVALID_ENVIRONMENT', 'not a Radiance .hdr ("#?" header) or OpenEXR file', { field });
  // The validated map's copy of the texels.
  budget.charge(image.width * image.height * 16, site, `the ${image.width} x ${image.height} environment map`);
  // The decoded texels are this call's own: zeroed in place (validation copies them anyway).
  if (negative === 'zero') {
    // Zeroed whether or not anyone asks for the report (`f?.(g())` would skip g without f).
    const report = zeroNegativeChannels(image.data);
    options.onNegativeTexels?.(report);
  }
  return validateEnvironmentMap(
    { width: image.width, height: image.height, data: image.data, intensity: options.intensity, rotationRadians: options.rotationRadians },
    field,
  );
}
