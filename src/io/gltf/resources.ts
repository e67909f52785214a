/**
 * Fetches a glTF asset and every external resource it names (glTF 2.0 section 3.1 "URIs": relative
 * URIs resolve against the asset's own location; data URIs carry their bytes inline). Everything
 * is addressed as a URL: file paths become file: URLs, read with node:fs (fetch has no file:
 * scheme in Node), http(s) and blob: URLs go through fetch. Node modules load lazily through
 * variable specifiers so browser bundles never resolve them (as src/post/png-node.ts does).
 */
import type * as NodeFs from 'node:fs/promises';
import type * as NodePath from 'node:path';
import type * as NodeUrl from 'node:url';
import { failGltf } from './errors.ts';

export function isNodeRuntime(): boolean {
  return typeof process !== 'undefined' && typeof process.versions?.node === 'string';
}

async function nodeModule<T>(specifier: string): Promise<T> {
  return (await import(specifier)) as T;
}

/** A string source: an absolute URL (scheme followed by ':') or, in Node, a file path. */
export async function sourceStringToUrl(source: string): Promise<URL> {
  // A Windows drive letter ("C:\") is a path, not a scheme.
  if (/^[a-z][a-z0-9+.-]+:/i.test(source)) return new URL(source);
  if (isNodeRuntime()) {
    const url = await nodeModule<typeof NodeUrl>('node:url');
    const path = await nodeModule<typeof NodePath>('node:path');
    return url.pathToFileURL(path.resolve(source));
  }
  const base = (globalThis as { location?: { href: string } }).location?.href;
  if (base === undefined) failGltf('', `cannot resolve ${JSON.stringify(source)} without a base URL`);
  return new URL(source, base);
}

/** Decodes a data URI (RFC 2397): base64 or percent-encoded payload. */
export function decodeDataUri(uri: string): Uint8Array | undefined {
  const comma = uri.indexOf(',');
  if (!uri.startsWith('data:') || comma < 0) return undefined;
  const meta = uri.slice(5, comma);
  const payload = uri.slice(comma + 1);
  if (/;base64$/i.test(meta)) {
    const clean = payload.replace(/\s+/g, '');
    if (!/^[A-Za-z0-9+/]*={0,2}$/.test(clean)) return undefined;
    const binary = atob(clean);
    const bytes = new Uint8Array(binary.length);
    for (let i = 0; i < binary.length; i++) bytes[i] = binary.charCodeAt(i);
    return bytes;
  }
  try {
    return new TextEncoder().encode(decodeURIComponent(payload));
  } catch {
    return undefined;
  }
}

/** Reads the bytes at `url`; rejects with the underlying error (the caller names the glTF field). */
export async function readUrl(url: URL, signal: AbortSignal | undefined): Promise<Uint8Array> {
  if (url.protocol === 'data:') {
    const bytes = decodeDataUri(url.href);
    if (bytes === undefined) throw new Error('malformed data URI');
    return bytes;
  }
  if (url.protocol === 'file:' && isNodeRuntime()) {
    const fs = await nodeModule<typeof NodeFs>('node:fs/promises');
    const nodeUrl = await nodeModule<typeof NodeUrl>('node:url');
    const data = await fs.readFile(nodeUrl.fileURLToPath(url), signal === undefined ? undefined : { signal });
    return new Uint8Array(data.buffer, data.byteOffset, data.byteLength);
  }
  const response = await fetch(url, signal === undefined ? undefined : { signal });
  if (!response.ok) throw new Error(`HTTP ${response.status} ${response.statusText}`);
  return new Uint8Array(await response.arrayBuffer());
}

/** Reads a resource the asset names by `uri`: inline data, or a location relative to `base`. */
export async function readResource(uri: string, base: URL | undefined, field: string, signal: AbortSignal | undefined): Promise<Uint8Array> {
  if (uri.startsWith('data:')) {
    const bytes = decodeDataUri(uri);
    if (bytes === undefined) failGltf(field, 'malformed data URI');
    return bytes;
  }
  if (base === undefined) {
    failGltf(field, `external resource ${JSON.stringify(uri)} cannot be resolved: the asset was given as bytes; pass a path or URL instead`);
  }
  let url: URL;
  try {
    url = new URL(uri, base);
  } catch (error) {
    failGltf(field, `invalid URI ${JSON.stringify(uri)}`, error);
  }
  try {
    return await readUrl(url, signal);
  } catch (error) {
    signal?.throwIfAborted();
    failGltf(field, `cannot read ${JSON.stringify(uri)} (${url.href}): ${(error as Error).message}`, error);
  }
}
