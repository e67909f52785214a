/**
 * The reads behind the resource policy (resource-policy.ts decides what may be read; this reads
 * it): a local file as a regular file of known size, and one fetch with a time limit and a size
 * cap whose redirects are checked hop by hop.
 */
import type * as NodeFs from 'node:fs';
import type * as NodeFsPromises from 'node:fs/promises';
import type * as NodePath from 'node:path';
import type * as NodeUrl from 'node:url';
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { isNodeRuntime, nodeModule } from './platform.ts';
import { refuse, refuseReach, type ResolvedResourcePolicy, type ResourceSite } from './resource-limits.ts';

function describeFsError(error: unknown): string {
  const e = error as { code?: string; message?: string };
  return e.code ?? e.message ?? String(error);
}

function fileKind(stat: NodeFs.Stats): string {
  if (stat.isDirectory()) return 'a directory';
  if (stat.isFIFO()) return 'a named pipe';
  if (stat.isCharacterDevice()) return 'a character device';
  if (stat.isBlockDevice()) return 'a block device';
  if (stat.isSocket()) return 'a socket';
  return 'not a regular file';
}

/** Node: whether real path `child` lies in real folder `parent`. */
function pathInside(path: typeof NodePath, parent: string, child: string): boolean {
  const rel = path.relative(parent, child);
  return rel === '' || (rel !== '..' && !rel.startsWith(`..${path.sep}`) && !path.isAbsolute(rel));
}

const READ_CHUNK = 1 << 24;

/**
 * Reads a regular file: realpath (and the real path inside each real folder of `confines`), stat
 * (regular file, size within the cap) and open without blocking or following a final link, then
 * fstat again and read exactly its size in chunks (the signal is checked between them). A file that
 * yields more bytes than its size (a /proc or /sys pseudo-file, or one growing) is refused.
 */
export async function readLocalFile(url: URL, confines: readonly URL[], policy: ResolvedResourcePolicy, site: ResourceSite, signal: AbortSignal | undefined, label: string | undefined): Promise<Uint8Array> {
  const maxBytes = policy.maxResourceBytes;
  const fs = await nodeModule<typeof NodeFsPromises>('node:fs/promises');
  const { constants } = await nodeModule<typeof NodeFs>('node:fs');
  const path = await nodeModule<typeof NodePath>('node:path');
  const nodeUrl = await nodeModule<typeof NodeUrl>('node:url');
  let file: string;
  try {
    file = nodeUrl.fileURLToPath(url);
  } catch (error) {
    refuse(site, `${label ?? url.href} is not a local file path (${(error as Error).message})`, error);
  }
  const shown = label ?? file;
  let real: string;
  try {
    real = await fs.realpath(file);
  } catch (error) {
    refuse(site, `cannot read ${shown}: ${describeFsError(error)}`, error);
  }
  const realRoots: string[] = [];
  for (const confine of confines) {
    let realRoot: string;
    try {
      realRoot = await fs.realpath(nodeUrl.fileURLToPath(confine));
    } catch (error) {
      refuse(site, `cannot resolve the folder ${confine.href}: ${describeFsError(error)}`, error);
    }
    if (!pathInside(path, realRoot, real)) refuseReach(site, `${shown} leads (through a symbolic link) to ${real}, outside the folder ${realRoot}`);
    realRoots.push(realRoot);
  }
  signal?.throwIfAborted();
  const before = await fs.stat(real).catch((error: unknown) => refuse(site, `cannot read ${shown}: ${describeFsError(error)}`, error));
  if (!before.isFile()) refuse(site, `${shown} is ${fileKind(before)}; only regular files are read`);
  if (before.size > maxBytes) refuse(site, `${shown} has ${before.size} bytes, over the resource limit of ${maxBytes} (resourcePolicy.maxResourceBytes)`);
  const flags = constants.O_RDONLY | (constants.O_NONBLOCK ?? 0) | (constants.O_NOFOLLOW ?? 0);
  const handle = await fs.open(real, flags).catch((error: unknown) => refuse(site, `cannot open ${shown}: ${describeFsError(error)}`, error));
  try {
    const stat = await handle.stat();
    if (!stat.isFile()) refuse(site, `${shown} is ${fileKind(stat)}; only regular files are read`);
    if (stat.size > maxBytes) refuse(site, `${shown} has ${stat.size} bytes, over the resource limit of ${maxBytes} (resourcePolicy.maxResourceBytes)`);
    if (realRoots.length > 0 && process.platform === 'linux') {
      // What was opened, whatever happened to the path since realpath().
      const opened = await fs.readlink(`/proc/self/fd/${handle.fd}`).catch(() => undefined);
      if (opened !== undefined && opened.startsWith('/') && realRoots.some((root) => !pathInside(path, root, opened))) refuseReach(site, `${shown} was replaced by a link to ${opened} while being opened`);
    }
    policy.budget?.charge(stat.size, site, `the ${stat.size} bytes of ${shown}`);
    const out = new Uint8Array(stat.size);
    let offset = 0;
    while (offset < out.length) {
      signal?.throwIfAborted();
      const { bytesRead } = await handle.read(out, offset, Math.min(READ_CHUNK, out.length - offset), offset);
      if (bytesRead === 0) refuse(site, `${shown} ended after ${offset} of its ${out.length} bytes (it shrank while being read)`);
      offset += bytesRead;
    }
    const probe = await handle.read(new Uint8Array(1), 0, 1, out.length);
    if (probe.bytesRead > 0) refuse(site, `${shown} yields more bytes than its size of ${out.length}: a pseudo-file (such as /proc or /sys) or a file growing while read; only regular files are read`);
    return out;
  } finally {
    await handle.close();
  }
}

/**
 * One fetch with the policy's timeout (the whole body included) and size cap. In Node redirects
 * are followed by hand so that each hop is checked with `redirectOk` before it is requested; in
 * browsers the platform follows them (within its own origin rules) and the final URL is checked.
 */
export async function fetchBytes(
  url: URL,
  policy: ResolvedResourcePolicy,
  site: ResourceSite,
  signal: AbortSignal | undefined,
  redirectOk: (next: URL) => boolean,
  label: string,
): Promise<Uint8Array> {
  const timeout = AbortSignal.timeout(policy.fetchTimeoutMs);
  const combined = signal === undefined ? timeout : AbortSignal.any([signal, timeout]);
  const manual = isNodeRuntime();
  function failed(what: string, error: unknown): never {
    signal?.throwIfAborted();
    if (timeout.aborted) refuse(site, `${what}: no complete response within ${policy.fetchTimeoutMs} ms (resourcePolicy.fetchTimeoutMs)`, error);
    refuse(site, `cannot fetch ${what === url.href ? label : what}: ${(error as Error).message}`, error);
  }
  let current = url;
  let response: Response;
  for (let hop = 0; ; hop++) {
    try {
      response = await fetch(current, { signal: combined, redirect: manual ? 'manual' : 'follow' });
    } catch (error) {
      failed(current.href, error);
    }
    if (!manual || response.status < 300 || response.status > 399 || response.status === 304) break;
    await response.body?.cancel().catch(() => undefined);
    const location = response.headers.get('location');
    if (location === null) refuse(site, `${current.href}: HTTP ${response.status} without a Location`);
    if (hop >= 5) refuse(site, `${url.href}: more than 5 redirects`);
    let next: URL;
    try {
      next = new URL(location, current);
    } catch (error) {
      refuse(site, `${current.href} redirects to an invalid URL`, error);
    }
    if (!redirectOk(next)) refuseReach(site, `${current.href} redirects to ${next.href}, where this load may not go (resourcePolicy.allowedOrigins)`);
    current = next;
  }
  if (!manual && response.redirected && response.url !== '' && !redirectOk(new URL(response.url))) {
    await response.body?.cancel().catch(() => undefined);
    refuseReach(site, `${url.href} was redirected to ${response.url}, where this load may not go (resourcePolicy.allowedOrigins)`);
  }
  if (!response.ok) {
    await response.body?.cancel().catch(() => undefined);
    refuse(site, `cannot fetch ${current.href === url.href ? label : current.href}: HTTP ${response.status} ${response.statusText}`.trimEnd());
  }
  const declared = Number(response.headers.get('content-length'));
  if (Number.isFinite(declared) && declared > policy.maxResourceBytes) {
    await response.body?.cancel().catch(() => undefined);
    refuse(site, `${current.href} declares ${declared} bytes, over the resource limit of ${policy.maxResourceBytes} (resourcePolicy.maxResourceBytes)`);
  }
  if (response.body === null) return new Uint8Array(0);
  const reader = response.body.getReader();
  const chunks: Uint8Array[] = [];
  let total = 0;
  try {
    for (;;) {
      const { done, value } = await reader.read();
      if (done) break;
      total += value.byteLength;
      policy.budget?.charge(value.byteLength, site, `the response of ${current.href}`);
      if (total > policy.maxResourceBytes) {
        await reader.cancel().catch(() => undefined);
        refuse(site, `${current.href} sent more than the resource limit of ${policy.maxResourceBytes} bytes (resourcePolicy.maxResourceBytes)`);
      }
      chunks.push(value);
    }
  } catch (error) {
    await reader.cancel().catch(() => undefined);
    if (error instanceof GpuRendererError) throw error;
    failed(current.href, error);
  }
  const out = new Uint8Array(total);
  let offset = 0;
  for (const chunk of chunks) {
    out.set(chunk, offset);
    offset += chunk.byteLength;
  }
  return out;
}
