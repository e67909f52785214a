/**
 * Where fuzz cases run and how escapes are seen. Each worker has a folder:
 *
 *   <run>/w<k>/asset/      the asset folder (case files are written here and removed after)
 *     sub/                 an empty subfolder
 *     link-out -> ../canary/secret.bin, link-dir -> ../canary, link-dev -> /dev/zero
 *     fifo                 a named pipe (a reader blocks until a writer comes)
 *   <run>/w<k>/canary/     files outside the asset folder: secret.bin, secret.png, secret.hdr
 *
 * A canary's access time is set before its modification time, so the first read of it moves the
 * access time (Linux relatime updates atime when it is older than mtime): a changed atime after a
 * case is an escape, seen by the file system rather than by instrumenting the loader. Network
 * escapes are seen by two local HTTP servers in the parent (run.ts): one no case may contact, and
 * one only cases whose policy allows its origin may.
 */
import { execFileSync } from 'node:child_process';
import { mkdirSync, rmSync, statSync, symlinkSync, utimesSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { encode as encodePng } from 'fast-png';

export interface WorkerSandbox {
  root: string;
  asset: string;
  canary: string;
  canaryFiles: string[];
  hasFifo: boolean;
}

export interface Servers {
  /** Origin no case may contact. */
  denied: string;
  /** Origin a case may contact when its policy allows it (serves /ok.bin, /slow, /huge, /redirect). */
  allowed: string;
}

const ARMED_ATIME = new Date('2001-01-01T00:00:00Z');

export function armCanary(path: string): void {
  utimesSync(path, ARMED_ATIME, new Date());
}

/** Canary files whose access time moved (read since they were armed); re-arms them. */
export function touchedCanaries(sandbox: WorkerSandbox): string[] {
  const touched: string[] = [];
  for (const file of sandbox.canaryFiles) {
    if (statSync(file).atimeMs !== ARMED_ATIME.getTime()) {
      touched.push(file);
      armCanary(file);
    }
  }
  return touched;
}

export function createWorkerSandbox(runDir: string, worker: number): WorkerSandbox {
  const root = join(runDir, `w${worker}`);
  rmSync(root, { recursive: true, force: true });
  const asset = join(root, 'asset');
  const canary = join(root, 'canary');
  mkdirSync(join(asset, 'sub'), { recursive: true });
  mkdirSync(canary, { recursive: true });
  const png = encodePng({ width: 2, height: 2, data: new Uint8Array(16).fill(200), channels: 4 });
  const files: Record<string, Uint8Array> = {
    'secret.bin': new Uint8Array(4096).fill(0x42),
    'secret.png': png,
    'secret.hdr': new TextEncoder().encode('#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 1\n\x80\x80\x80\x81'),
  };
  const canaryFiles: string[] = [];
  for (const [name, bytes] of Object.entries(files)) {
    const path = join(canary, name);
    writeFileSync(path, bytes);
    armCanary(path);
    canaryFiles.push(path);
  }
  symlinkSync('../canary/secret.bin', join(asset, 'link-out'));
  symlinkSync('../canary', join(asset, 'link-dir'));
  symlinkSync('/dev/zero', join(asset, 'link-dev'));
  let hasFifo: boolean;
  try {
    execFileSync('mkfifo', [join(asset, 'fifo')]);
    hasFifo = true;
  } catch {
    hasFifo = false;
  }
  return { root, asset, canary, canaryFiles, hasFifo };
}

/**
 * References an attacker writes into an asset: `$CANARY` is the canary folder's absolute path,
 * `$DENIED` and `$ALLOWED` the servers' origins, `$CASE` the case's tag (so a request names its
 * case). Relative ones resolve against the asset folder.
 */
export const HOSTILE_URIS: readonly string[] = [
  '../canary/secret.bin',
  '../canary/secret.png',
  'sub/../../canary/secret.bin',
  '%2e%2e/canary/secret.bin',
  '.%2e/canary/secret.png',
  'sub/%2E%2E/%2E%2E/canary/secret.bin',
  '..%2fcanary%2fsecret.bin',
  '..%5ccanary%5csecret.bin',
  '..\\canary\\secret.bin',
  'sub\\..\\..\\canary\\secret.png',
  '$CANARY/secret.bin',
  '$CANARY/secret.png',
  'file://$CANARY/secret.bin',
  'file:$CANARY/secret.png',
  'FILE://localhost$CANARY/secret.bin',
  'link-out',
  'link-dir/secret.png',
  'link-dev',
  'fifo',
  'sub',
  '.',
  './',
  '',
  '/dev/zero',
  '/dev/urandom',
  '/proc/self/environ',
  '/proc/self/status',
  '/etc/passwd',
  '$DENIED/$CASE/x.bin',
  '$DENIED/$CASE/x.png',
  '//127.0.0.1:$DENIED_PORT/$CASE/y.bin',
  'http://localhost:$DENIED_PORT/$CASE/z.bin',
  'HTTP://127.0.0.1:$DENIED_PORT/$CASE/w.bin',
  'http://user:pw@127.0.0.1:$ALLOWED_PORT/$CASE/ok.bin',
  '$ALLOWED/$CASE/ok.bin',
  '$ALLOWED/$CASE/ok.png',
  '$ALLOWED/$CASE/redirect',
  '$ALLOWED/$CASE/slow',
  '$ALLOWED/$CASE/huge',
  'data:application/octet-stream;base64,A',
  'data:application/octet-stream;base64,AAAA====',
  'data:;base64,@@@@',
  'data:,%ZZ',
  'data:',
  'data:application/octet-stream,%00%01',
  'javascript:alert(1)',
  'ftp://127.0.0.1/x',
  'blob:nope',
  'C:\\Windows\\win.ini',
  'c:/x.bin',
  '\\\\127.0.0.1\\share\\x.bin',
  'asset.bin?x=1#y',
  'asset.bin%00.png',
  'asset%2ebin',
  'sub/%2e%2e/asset.bin',
];

/**
 * Sources a caller could be tricked into passing that must be refused even as the caller's own
 * choice: devices, pipes, pseudo-files, folders, schemes that are never read.
 */
export const HOSTILE_SOURCES: readonly string[] = [
  '/dev/zero',
  '/dev/urandom',
  '/dev/stdin',
  '/proc/self/status',
  '/proc/self/environ',
  '/sys/kernel/mm/transparent_hugepage/enabled',
  '$ASSET/fifo',
  '$ASSET/link-dev',
  '$ASSET/sub',
  '$ASSET',
  'javascript:alert(1)',
  'ftp://127.0.0.1/x.glb',
  'data:model/gltf+json;base64,@@',
];

export interface UriContext {
  canary: string;
  asset: string;
  servers: Servers;
  caseTag: string;
}

export function expandUri(template: string, context: UriContext): string {
  const port = (origin: string): string => new URL(origin).port;
  return template
    .replaceAll('$CANARY', context.canary)
    .replaceAll('$ASSET', context.asset)
    .replaceAll('$DENIED_PORT', port(context.servers.denied))
    .replaceAll('$ALLOWED_PORT', port(context.servers.allowed))
    .replaceAll('$DENIED', context.servers.denied)
    .replaceAll('$ALLOWED', context.servers.allowed)
    .replaceAll('$CASE', context.caseTag);
}
