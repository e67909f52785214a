/**
 * Path mapping for farm workers that mount shared storage elsewhere than the submitting machine
 * (Deadline's path mapping, Flamenco's two-way variables): a job's path under FROM is read as the
 * same path under TO, the longest matching FROM winning, whole path segments only.
 */
import { isAbsolute, relative, resolve, sep } from 'node:path';
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';

function invalid(field: string, message: string): never {
  throw new GpuRendererError('INVALID_OPTION', message, { field });
}

/** A path-map entry: a job path under `from` is read as the same path under `to`. */
export interface FarmPathMapping {
  from: string;
  to: string;
}

/** `FROM=TO` (split at the first '='; both absolute), as `--path-map` and GPU_RENDERER_FARM_PATH_MAP write it. */
export function parsePathMapping(text: string, field: string): FarmPathMapping {
  const at = text.indexOf('=');
  if (at <= 0 || at === text.length - 1) invalid(field, `expected FROM=TO (two absolute paths), got ${JSON.stringify(text)}`);
  return checkPathMapping({ from: text.slice(0, at), to: text.slice(at + 1) }, field);
}

export function checkPathMapping(mapping: FarmPathMapping, field: string): FarmPathMapping {
  if (typeof mapping?.from !== 'string' || typeof mapping.to !== 'string' || !isAbsolute(mapping.from) || !isAbsolute(mapping.to)) {
    invalid(field, `a path map entry maps one absolute path to another, got ${JSON.stringify(mapping)}`);
  }
  return { from: resolve(mapping.from), to: resolve(mapping.to) };
}

/** Whether `path` is `root` or lies below it (both resolved). */
export function isUnder(path: string, root: string): boolean {
  const r = relative(root, path);
  return r === '' || (!r.startsWith(`..${sep}`) && r !== '..' && !isAbsolute(r));
}

/** A job's absolute path with the longest matching FROM prefix replaced by its TO (whole path segments only). */
export function mapJobPath(path: string, pathMap: readonly FarmPathMapping[]): string {
  const normal = resolve(path);
  let best: FarmPathMapping | undefined;
  for (const mapping of pathMap) {
    if (isUnder(normal, mapping.from) && (best === undefined || mapping.from.length > best.from.length)) best = mapping;
  }
  return best === undefined ? normal : resolve(best.to, relative(best.from, normal));
}

