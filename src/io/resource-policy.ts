/**
 * What the loaders may touch. Every loader (glTF, scene JSON, environment maps, the CLI) reads
 * through this module, so one policy decides for all of them:
 *
 * - The source the caller names (a path, a URL, bytes) is read as asked: a regular file (stat
 *   first: devices, pipes and /proc-like pseudo-files are refused) or one fetch, size-capped, with a
 *   timeout. With `root`, the source and every reference it makes must lie inside that folder too
 *   (after symbolic links).
 * - A reference an asset makes (a glTF buffer or image `uri`, a scene file's `images[].uri`,
 *   `environment.map` or `gltf[].src`) is a data URI, or a relative URI reference (RFC 3986 section
 *   4.2) resolving inside the asset's own folder (glTF 2.0 section 3.1: relative to the asset's
 *   location), after percent-decoding and, on disk, after symbolic links. Absolute paths, `file:`
 *   URLs, other schemes, `..` that climbs out, encoded separators and links leaving the folder are
 *   refused. A network reference outside the folder is fetched only when its origin is in
 *   `allowedOrigins`; redirects are followed only where a reference could go itself.
 * - Budgets: bytes per resource, decoded bytes per load (accessor arrays, image texels, environment
 *   maps), image sides; a load beyond them is refused before allocating.
 *
 * Faults are `GpuRendererError`s with the loader's code and field (a JSON pointer for glTF). An
 * `AbortSignal` ends file reads between chunks and fetches at once; it rejects with its reason.
 */
import type * as NodePath from 'node:path';
import type * as NodeUrl from 'node:url';
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { describe } from '../errors/validate.ts';
import { decodeDataUri } from './data-uri.ts';
import { isNodeRuntime, nodeModule } from './platform.ts';
import { DecodeBudget, refuse, refuseReach, type ResolvedResourcePolicy, type ResourceSite } from './resource-limits.ts';
import { fetchBytes, readLocalFile } from './resource-read.ts';

export { DecodeBudget, isReachRefusal, refuse, type ResolvedResourcePolicy, type ResourceSite } from './resource-limits.ts';

/** The `resourcePolicy` option of every loader. */
export interface ResourcePolicy {
  /**
   * Origins (`https://cdn.example.com`, `http://127.0.0.1:8080`) whose URLs an asset may reference
   * beyond its own folder. Default none: an asset on disk makes no network request, and an asset
   * fetched from a URL fetches only inside its own folder.
   */
  allowedOrigins?: readonly string[];
  /**
   * A folder (path or URL) every read must stay inside, the source itself included (after symbolic
   * links). Default none for the source; references stay inside their asset's folder regardless.
   */
  root?: string | URL;
  /** Largest file, response body or data URI read, in bytes. Default 2 GiB. */
  maxResourceBytes?: number;
  /** Bytes one load may read and decode in all (resources, parsed JSON, accessor arrays, image texels, maps). Default 2 GiB. */
  maxDecodedBytes?: number;
  /** Largest image width or height, in texels, read from the header before decoding. Default 16384. */
  maxImageDimension?: number;
  /** Time limit of each network request, body included, in milliseconds. Default 60000. */
  fetchTimeoutMs?: number;
  /**
   * Time limit of a decoder that cannot be trusted to end on corrupt data (OpenEXR's, run in a
   * worker thread in Node), in milliseconds. Default 60000.
   */
  decodeTimeoutMs?: number;
}

const resolvedPolicies = new WeakSet<object>();

function markResolved(policy: ResolvedResourcePolicy): ResolvedResourcePolicy {
  Object.freeze(policy);
  resolvedPolicies.add(policy);
  return policy;
}

export const defaultResourcePolicy: ResolvedResourcePolicy = markResolved({
  allowedOrigins: Object.freeze([]) as readonly string[],
  root: undefined,
  maxResourceBytes: 2 ** 31,
  maxDecodedBytes: 2 ** 31,
  maxImageDimension: 16384,
  fetchTimeoutMs: 60_000,
  decodeTimeoutMs: 60_000,
});

/** The same policy with another root and/or a budget shared with the load that derives it. */
export function derivePolicy(policy: ResolvedResourcePolicy, changes: { root?: URL | undefined; budget?: DecodeBudget }): ResolvedResourcePolicy {
  return markResolved({ ...policy, ...changes });
}

/** The policy's shared budget, or a new one for this load. */
export function budgetOf(policy: ResolvedResourcePolicy): DecodeBudget {
  return policy.budget ?? new DecodeBudget(policy.maxDecodedBytes);
}

const KEYS = ['allowedOrigins', 'root', 'maxResourceBytes', 'maxDecodedBytes', 'maxImageDimension', 'fetchTimeoutMs', 'decodeTimeoutMs'];

/** Checks a `resourcePolicy` option (INVALID_OPTION naming `field.key`) and fills in the defaults. */
export async function resolveResourcePolicy(input: unknown, field = 'resourcePolicy'): Promise<ResolvedResourcePolicy> {
  if (input === undefined) return defaultResourcePolicy;
  if (typeof input === 'object' && input !== null && resolvedPolicies.has(input)) return input as ResolvedResourcePolicy;
  function invalid(at: string, message: string): never {
    throw new GpuRendererError('INVALID_OPTION', message, { field: at });
  }
  if (typeof input !== 'object' || input === null || Array.isArray(input)) invalid(field, `expected an object, got ${describe(input)}`);
  const o = input as Record<string, unknown>;
  for (const key of Object.keys(o)) if (!KEYS.includes(key)) invalid(`${field}.${key}`, `unknown key (expected one of ${KEYS.join(', ')})`);
  const positive = (key: string, fallback: number, max = Number.MAX_SAFE_INTEGER): number => {
    const v = o[key];
    if (v === undefined) return fallback;
    if (typeof v !== 'number' || !Number.isInteger(v) || v < 1 || v > max) invalid(`${field}.${key}`, `expected an integer in 1..${max}, got ${describe(v)}`);
    return v as number;
  };
  let allowedOrigins: readonly string[] = [];
  if (o.allowedOrigins !== undefined) {
    if (!Array.isArray(o.allowedOrigins)) invalid(`${field}.allowedOrigins`, `expected an array of origins, got ${describe(o.allowedOrigins)}`);
    allowedOrigins = (o.allowedOrigins as unknown[]).map((origin, i) => parseOrigin(origin, `${field}.allowedOrigins[${i}]`));
  }
  let root: URL | undefined;
  if (o.root !== undefined) {
    if (!(o.root instanceof URL) && (typeof o.root !== 'string' || o.root === '')) invalid(`${field}.root`, `expected a folder path or URL, got ${describe(o.root)}`);
    root = await locateSource(o.root as string | URL, { code: 'INVALID_OPTION', field: `${field}.root` });
    if (!root.pathname.endsWith('/')) root = new URL(`${root.pathname}/${root.search}`, root);
  }
  return markResolved({
    allowedOrigins: Object.freeze(allowedOrigins),
    root,
    maxResourceBytes: positive('maxResourceBytes', defaultResourcePolicy.maxResourceBytes),
    maxDecodedBytes: positive('maxDecodedBytes', defaultResourcePolicy.maxDecodedBytes),
    maxImageDimension: positive('maxImageDimension', defaultResourcePolicy.maxImageDimension, 65536),
    fetchTimeoutMs: positive('fetchTimeoutMs', defaultResourcePolicy.fetchTimeoutMs, 2 ** 31 - 1),
    decodeTimeoutMs: positive('decodeTimeoutMs', defaultResourcePolicy.decodeTimeoutMs, 2 ** 31 - 1),
  });
}

/** `https://host[:port]` from an origin or URL string; paths, queries and credentials are refused. */
export function parseOrigin(value: unknown, field: string): string {
  function invalid(message: string): never {
    throw new GpuRendererError('INVALID_OPTION', message, { field });
  }
  if (typeof value !== 'string') return invalid(`expected an origin such as "https://cdn.example.com", got ${describe(value)}`);
  let url: URL;
  try {
    url = new URL(value);
  } catch {
    return invalid(`expected an origin such as "https://cdn.example.com", got ${describe(value)}`);
  }
  if (url.protocol !== 'http:' && url.protocol !== 'https:') invalid(`only http and https origins can be allowed, got ${describe(value)}`);
  if (url.username !== '' || url.password !== '' || (url.pathname !== '/' && url.pathname !== '') || url.search !== '' || url.hash !== '') {
    invalid(`expected an origin (scheme, host and port) without path, query or credentials, got ${describe(value)}`);
  }
  return url.origin;
}

/**
 * A string source as a URL: an absolute URL (a scheme followed by ':'), or a path (Node: against the
 * working directory; browsers: against the document). A Windows drive letter ("C:\") is a path.
 */
export async function locateSource(source: string | URL, site: ResourceSite): Promise<URL> {
  if (source instanceof URL) return new URL(source.href);
  if (/^[a-z][a-z0-9+.-]+:/i.test(source)) {
    try {
      return new URL(source);
    } catch (error) {
      refuse(site, `invalid URL ${JSON.stringify(source)}`, error);
    }
  }
  if (isNodeRuntime()) {
    const url = await nodeModule<typeof NodeUrl>('node:url');
    const path = await nodeModule<typeof NodePath>('node:path');
    return url.pathToFileURL(path.resolve(source));
  }
  const base = (globalThis as { location?: { href: string } }).location?.href;
  if (base === undefined) refuse(site, `cannot resolve ${JSON.stringify(source)} without a base URL`);
  try {
    return new URL(source, base);
  } catch (error) {
    refuse(site, `invalid URL ${JSON.stringify(source)}`, error);
  }
}

/** The folder of an asset (its URL up to the last '/'); references must stay inside it. */
export function folderOf(url: URL): URL | undefined {
  if (url.protocol !== 'file:' && url.protocol !== 'http:' && url.protocol !== 'https:') return undefined;
  const folder = new URL('./', url);
  folder.search = '';
  folder.hash = '';
  return folder;
}

/** Whether `url` lies inside `folder` (same scheme and origin, path under the folder's). */
export function isInsideFolder(url: URL, folder: URL): boolean {
  return url.protocol === folder.protocol && url.host === folder.host && url.username === folder.username && url.password === folder.password && url.pathname.startsWith(folder.pathname);
}

function isAllowedOrigin(url: URL, policy: ResolvedResourcePolicy): boolean {
  return (url.protocol === 'http:' || url.protocol === 'https:') && url.username === '' && url.password === '' && policy.allowedOrigins.includes(url.origin);
}

/**
 * The URL a reference names, if the policy lets the asset at `asset` read it; otherwise a typed
 * error at `site` saying why. `asset` undefined: the asset was given as bytes and has no location.
 * Data URIs are not handled here (see `readReference`).
 */
export function resolveReference(uri: string, asset: URL | undefined, policy: ResolvedResourcePolicy, site: ResourceSite): URL {
  const shown = JSON.stringify(uri.length > 120 ? `${uri.slice(0, 120)}...` : uri);
  if (asset === undefined) refuse(site, `external resource ${shown} cannot be resolved: the asset was given as bytes; pass a path or URL instead`);
  const folder = folderOf(asset);
  if (uri === '') refuse(site, 'an empty URI names no resource');
  if ([...uri].some((ch) => ch.charCodeAt(0) < 0x20)) refuse(site, `${shown} contains control characters`);
  const scheme = /^([a-z][a-z0-9+.-]*):/i.exec(uri)?.[1]?.toLowerCase();
  if (scheme !== undefined) {
    let url: URL;
    try {
      url = new URL(uri);
    } catch (error) {
      refuse(site, `invalid URI ${shown}`, error);
    }
    if (isAllowedOrigin(url, policy)) return url;
    if ((scheme === 'http' || scheme === 'https') && folder !== undefined && isInsideFolder(url, folder) && asset.protocol === url.protocol) return url;
    if (scheme === 'http' || scheme === 'https') {
      refuseReach(site, `${shown} is on ${url.origin}, which the resource policy does not allow (resourcePolicy.allowedOrigins; CLI --allow-origin)`);
    }
    if (scheme.length === 1) refuseReach(site, `${shown} is an absolute path; references must be relative to the asset's folder`);
    refuseReach(site, `${shown}: ${scheme}: URIs are not read; references are relative to the asset's folder, data: URIs, or URLs of allowed origins`);
  }
  if (uri.startsWith('//') || uri.startsWith('\\\\')) {
    // A network-path reference (RFC 3986 section 4.2): another host with the asset's scheme.
    let url: URL | undefined;
    try {
      url = new URL(uri, asset);
    } catch {
      url = undefined;
    }
    if (url !== undefined && isAllowedOrigin(url, policy)) return url;
    refuseReach(site, `${shown} names another host; references must be relative to the asset's folder (or on an allowed origin)`);
  }
  if (uri.startsWith('/') || uri.startsWith('\\')) refuseReach(site, `${shown} is an absolute path; references must be relative to the asset's folder`);
  if (folder === undefined) refuse(site, `${shown} cannot be resolved against ${asset.protocol} ${asset.protocol === 'data:' ? 'data' : 'URLs'}`);
  // Each path segment, percent-decoded, must be a plain name: no encoded separator, NUL or malformed escape.
  const path = uri.replace(/[?#].*$/s, '');
  for (const segment of path.split(/[/\\]/)) {
    let decoded: string;
    try {
      decoded = decodeURIComponent(segment);
    } catch {
      refuse(site, `${shown} has a malformed percent-encoding`);
    }
    if (decoded.includes('/') || decoded.includes('\\') || decoded.includes('\0')) refuse(site, `${shown} hides a path separator or NUL in a percent-encoded segment`);
  }
  let url: URL;
  try {
    url = new URL(uri, asset);
  } catch (error) {
    refuse(site, `invalid URI ${shown}`, error);
  }
  if (!isInsideFolder(url, folder)) refuseReach(site, `${shown} resolves to ${url.href}, outside the asset's folder ${folder.href}`);
  return url;
}

/** Reads the source the caller named (a URL from `locateSource`), under the policy's limits. */
export async function readSource(url: URL, policy: ResolvedResourcePolicy, site: ResourceSite, signal?: AbortSignal): Promise<Uint8Array> {
  signal?.throwIfAborted();
  if (url.protocol === 'data:') return dataBytes(url.href, policy, site);
  if (policy.root !== undefined && !isInsideFolder(url, policy.root) && !isAllowedOrigin(url, policy)) {
    refuseReach(site, `${url.href} lies outside the resource policy's root ${policy.root.href}`);
  }
  return readLocation(url, policy.root !== undefined && !isAllowedOrigin(url, policy) ? [policy.root] : [], policy, site, signal, url, url.protocol === 'file:' ? undefined : url.href);
}

/** What the loaders accept as a file: a path (Node), a URL (fetched), or the file's bytes. */
export type ByteSource = string | URL | ArrayBuffer | Uint8Array;

/**
 * The one "read a path or URL" step of every loader: bytes are taken as they are; a path or URL
 * is located (`locateSource`) and read under the policy (`readSource`). `url` is where the bytes
 * came from (relative references resolve against it), undefined for bytes.
 */
export async function readByteSource(source: ByteSource, policy: ResolvedResourcePolicy, site: ResourceSite, signal?: AbortSignal): Promise<{ bytes: Uint8Array; url: URL | undefined }> {
  if (source instanceof Uint8Array) return { bytes: source, url: undefined };
  if (source instanceof ArrayBuffer) return { bytes: new Uint8Array(source), url: undefined };
  if (typeof source !== 'string' && !(source instanceof URL)) refuse(site, `expected a path, a URL, an ArrayBuffer or a Uint8Array, got ${describe(source)}`);
  const url = await locateSource(source, site);
  return { bytes: await readSource(url, policy, site, signal), url };
}

/** Reads what an asset at `asset` names by `uri`, under the policy (see `resolveReference`). */
export async function readReference(uri: string, asset: URL | undefined, policy: ResolvedResourcePolicy, site: ResourceSite, signal?: AbortSignal): Promise<Uint8Array> {
  signal?.throwIfAborted();
  if (/^data:/i.test(uri)) return dataBytes(uri, policy, site);
  const url = resolveReference(uri, asset, policy, site);
  const folder = folderOf(asset!);
  const shown = JSON.stringify(uri.length > 120 ? `${uri.slice(0, 120)}...` : uri);
  // The root bounds every read, the asset's references too (an asset whose folder is a link out of the root reads nothing there).
  const rooted = policy.root !== undefined && !isAllowedOrigin(url, policy);
  if (rooted && !isInsideFolder(url, policy.root!)) refuseReach(site, `${shown} (${url.href}) lies outside the resource policy's root ${policy.root!.href}`);
  const confines = [...(folder !== undefined && isInsideFolder(url, folder) ? [folder] : []), ...(rooted ? [policy.root!] : [])];
  return readLocation(url, confines, policy, site, signal, asset!, `${shown} (${url.href})`);
}

function dataBytes(uri: string, policy: ResolvedResourcePolicy, site: ResourceSite): Uint8Array {
  // Base64 carries 3 bytes per 4 characters: charge the most it can decode to before decoding.
  policy.budget?.charge(Math.ceil((uri.length * 3) / 4), site, 'the data URI\'s bytes');
  const result = decodeDataUri(uri, policy.maxResourceBytes);
  if ('error' in result) refuse(site, `malformed data URI: ${result.error}`);
  return result.bytes;
}

/** `label` names the resource in messages (default: its path or URL). */
async function readLocation(
  url: URL,
  confines: readonly URL[],
  policy: ResolvedResourcePolicy,
  site: ResourceSite,
  signal: AbortSignal | undefined,
  origin: URL,
  label: string | undefined,
): Promise<Uint8Array> {
  if (url.protocol === 'file:') {
    if (!isNodeRuntime()) refuse(site, `${url.href}: file: URLs are read in Node.js only; pass a URL or the bytes`);
    return readLocalFile(url, confines, policy, site, signal, label);
  }
  if (url.protocol === 'http:' || url.protocol === 'https:' || url.protocol === 'blob:') {
    // A redirect may go where a reference could go itself: inside the folder, the same origin as
    // the caller's own source, or an allowed origin.
    const redirectOk = (next: URL): boolean => isAllowedOrigin(next, policy) || (confines.length > 0 ? confines.every((folder) => isInsideFolder(next, folder)) : next.origin === origin.origin);
    return fetchBytes(url, policy, site, signal, redirectOk, label ?? url.href);
  }
  refuse(site, `${url.protocol} URLs are not read (file paths, http(s), blob: and data: URIs are)`);
}
