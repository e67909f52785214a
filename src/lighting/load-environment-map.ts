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
  const bytes = await readSource(source, field);
  let image;
  if (isRadianceHdr(bytes)) image = decodeRadianceHdr(bytes, field);
  else if (isOpenExr(bytes)) image = await decodeOpenExr(bytes, field, options.EXRLoader);
  else throw new GpuRendererError('INVALID_ENVIRONMENT', 'not a Radiance .hdr ("#?" header) or OpenEXR file', { field });
  return validateEnvironmentMap(
    { width: image.width, height: image.height, data: image.data, intensity: options.intensity, rotationRadians: options.rotationRadians },
    field,
  );
}
