/**
 * The platform checks and Node built-ins, in one place. The package runs in browsers, workers and
 * Node.js; whatever needs Node (files, worker threads, Dawn) asks here first, and imports built-ins
 * through a variable specifier so that browser bundlers never try to resolve them.
 */
import type * as NodeFsPromises from 'node:fs/promises';
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';

/** True in Node.js (and runtimes that present themselves as Node, such as Deno's and Bun's). */
export function isNodeRuntime(): boolean {
  return typeof process !== 'undefined' && typeof process.versions?.node === 'string';
}

/** A Node built-in (or Node-only package) through a variable specifier, so browser bundlers never resolve it. */
export async function nodeModule<T>(specifier: string): Promise<T> {
  // The comments keep Vite and webpack from warning about (or trying to resolve) the specifier.
  return (await import(/* @vite-ignore */ /* webpackIgnore: true */ specifier)) as T;
}

/**
 * Throws `INVALID_STATE` outside Node.js: `what` says what needs Node, `alternative` what a
 * browser can call instead (both end up in the message).
 */
export function requireNodeRuntime(what: string, alternative?: string): void {
  if (isNodeRuntime()) return;
  throw new GpuRendererError('INVALID_STATE', `${what} needs Node.js (node:fs)${alternative === undefined ? '' : `; ${alternative}`}`);
}

/** `node:fs/promises`, after `requireNodeRuntime(what, alternative)`. */
export async function nodeFileSystem(what: string, alternative?: string): Promise<typeof NodeFsPromises> {
  requireNodeRuntime(what, alternative);
  return nodeModule<typeof NodeFsPromises>('node:fs/promises');
}

/** Writes `bytes` to the file at `path` (Node.js only; `what` names the caller in the error elsewhere). */
export async function writeFileBytes(path: string, bytes: Uint8Array, what: string, alternative?: string): Promise<void> {
  const fs = await nodeFileSystem(what, alternative);
  await fs.writeFile(path, bytes);
}
