import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { validateEnvironmentMap, type EnvironmentMap } from './environment-map.ts';
import { decodeOpenExr, isOpenExr, type ExrLoaderConstructor } from './openexr.ts';
import { decodeRadianceHdr, isRadianceHdr } from './radiance-hdr.ts';

/** Where an environment map comes from: a file path (Node), a URL (fetched), or the file's bytes. */
export type EnvironmentMapSource = string | URL | ArrayBuffer | Uint8Array;

export interface LoadEnvironmentMapOptions {
  /** Radiance multiplier, default 1. */
  intensity?: number;
  /** Rotation about +Y in radians, default 0. */
  rotationRadians?: number;
  /** three.js's EXRLoader class, for bundled browser apps (see openexr.ts); Node imports it itself. */
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
}

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

const isNode = (): boolean => typeof process !== 'undefined' && typeof process.versions?.node === 'string';

async function readSource(source: EnvironmentMapSource, field: string): Promise<Uint8Array> {
  if (source instanceof Uint8Array) return source;
  if (source instanceof ArrayBuffer) return new Uint8Array(source);
  const url = source instanceof URL ? source : /^[a-z][a-z0-9+.-]*:/i.test(source) && !/^[a-z]:[\\/]/i.test(source) ? new URL(source) : undefined;
  if (typeof source === 'string' && url === undefined && !isNode()) {
    // A relative URL in a browser or worker: fetch resolves it against the document.
    return fetchBytes(source, field);
  }
  if (url === undefined || url.protocol === 'file:') {
    if (!isNode()) throw new GpuRendererError('INVALID_ENVIRONMENT', 'file paths need Node.js; pass a URL or the bytes', { field });
    const specifier = 'node:fs/promises';
    const fs = (await import(specifier)) as { readFile: (path: string | URL) => Promise<Uint8Array> };
    try {
      return new Uint8Array(await fs.readFile(url ?? (source as string)));
    } catch (cause) {
      throw new GpuRendererError('INVALID_ENVIRONMENT', `cannot read ${String(source)}: ${(cause as Error).message}`, { field, cause });
    }
  }
  return fetchBytes(url.href, field);
}

async function fetchBytes(href: string, field: string): Promise<Uint8Array> {
  let response: Response;
  try {
    response = await fetch(href);
  } catch (cause) {
    throw new GpuRendererError('INVALID_ENVIRONMENT', `cannot fetch ${href}: ${(cause as Error).message}`, { field, cause });
  }
  if (!response.ok) throw new GpuRendererError('INVALID_ENVIRONMENT', `cannot fetch ${href}: HTTP ${response.status}`, { field });
  return new Uint8Array(await response.arrayBuffer());
}

/**
 * Loads a Radiance .hdr or OpenEXR environment map (format told by the file's signature) from a
 * path, URL or bytes, and validates it as an `environmentMap` (equirectangular, top row = +Y).
 * Unreadable, truncated or unknown files, and texels that are negative or not finite, raise
 * `INVALID_ENVIRONMENT` errors.
 */
export async function loadEnvironmentMap(source: EnvironmentMapSource, options: LoadEnvironmentMapOptions = {}): Promise<EnvironmentMap> {
  const field = options.field ?? 'source';
  if (!(typeof source === 'string' || source instanceof URL || source instanceof ArrayBuffer || source instanceof Uint8Array)) {
    throw new GpuRendererError('INVALID_ENVIRONMENT', 'expected a path, a URL, an ArrayBuffer or a Uint8Array', { field });
  }
  const policy = options.negativeTexels ?? 'error';
  if (policy !== 'error' && policy !== 'zero') throw new GpuRendererError('INVALID_OPTION', `expected 'error' or 'zero', got ${String(policy)}`, { field: 'negativeTexels' });
  const bytes = await readSource(source, field);
  let image;
  if (isRadianceHdr(bytes)) image = decodeRadianceHdr(bytes, field);
  else if (isOpenExr(bytes)) image = await decodeOpenExr(bytes, field, options.EXRLoader);
  else throw new GpuRendererError('INVALID_ENVIRONMENT', 'not a Radiance .hdr ("#?" header) or OpenEXR file', { field });
  // The decoded texels are this call's own: zeroed in place (validation copies them anyway).
  if (policy === 'zero') {
    // Zeroed whether or not anyone asks for the report (`f?.(g())` would skip g without f).
    const report = zeroNegativeChannels(image.data);
    options.onNegativeTexels?.(report);
  }
  return validateEnvironmentMap(
    { width: image.width, height: image.height, data: image.data, intensity: options.intensity, rotationRadians: options.rotationRadians },
    field,
  );
}
