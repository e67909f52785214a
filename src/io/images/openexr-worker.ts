/**
 * three.js's EXRLoader run in a Node worker thread that is terminated at a deadline. Its Huffman
 * decoder (PIZ, and DWAA/DWAB's AC coefficients) can loop forever on corrupt data inside a
 * well-formed file: when a run would overflow the output, getCode returns without updating the bit
 * state, and hufDecode retries the same bits. No validation of the container can rule that out, and
 * a synchronous loop cannot be interrupted on the thread running it, so the decoder runs where it
 * can be stopped.
 *
 * The worker is inline (eval'd source, as accel/bvh-worker-pool.ts does) and imports EXRLoader
 * by file URL, resolved from this package's own location, so the application's working directory
 * does not matter. Where no worker can be started or three.js cannot be found there, the caller
 * decodes on its own thread (after the structural validation of openexr-header.ts).
 */

import type * as NodeModule from 'node:module';
import type * as NodeUrl from 'node:url';
import { isNodeRuntime, nodeModule } from '../platform.ts';

/** What EXRLoader.parse returns, as the worker posts it back. */
export interface ParsedExr {
  width: number;
  height: number;
  data: Float32Array | Uint16Array;
  format?: number;
}

export type WorkerParse = { parsed: ParsedExr } | { error: string } | { timedOut: true } | { unavailable: string };

const SOURCE = `"use strict";
const { parentPort, workerData } = require('node:worker_threads');
(async () => {
  let module;
  try {
    module = await import(workerData.loaderUrl);
  } catch (error) {
    parentPort.postMessage({ unavailable: String(error && error.message) });
    return;
  }
  try {
    const loader = new module.EXRLoader();
    loader.setDataType(${1015});
    const r = loader.parse(workerData.buffer);
    parentPort.postMessage({ parsed: { width: r.width, height: r.height, format: r.format, data: r.data } }, [r.data.buffer]);
  } catch (error) {
    parentPort.postMessage({ error: String(error && error.message) });
  }
})();
`;

interface NodeWorker {
  on(event: 'message', listener: (message: WorkerParse) => void): void;
  on(event: 'error', listener: (error: Error) => void): void;
  on(event: 'exit', listener: (code: number) => void): void;
  terminate(): Promise<number>;
}

/** The file calling this (from a stack frame): this module's own path, in ESM and CommonJS builds alike. */
function ownFile(): string | undefined {
  const frames = (new Error().stack ?? '').split('\n').slice(1);
  for (const frame of frames) {
    const m = /\(?((?:file:\/\/)?\/[^\s()]+?):\d+:\d+\)?\s*$/.exec(frame);
    if (m !== null) return m[1];
  }
  return undefined;
}

let loaderUrl: Promise<string | undefined> | undefined;

/** The file URL of three's EXRLoader as this package resolves it, or undefined. */
function resolveLoaderUrl(): Promise<string | undefined> {
  loaderUrl ??= (async () => {
    try {
      const { createRequire } = await nodeModule<typeof NodeModule>('node:module');
      const { pathToFileURL, fileURLToPath } = await nodeModule<typeof NodeUrl>('node:url');
      const here = ownFile();
      const from = here === undefined ? `${process.cwd()}/` : here.startsWith('file:') ? fileURLToPath(here) : here;
      return pathToFileURL(createRequire(from).resolve('three/examples/jsm/loaders/EXRLoader.js')).href;
    } catch {
      return undefined;
    }
  })();
  return loaderUrl;
}

/**
 * Parses `buffer` (transferred: the caller passes its own copy) with EXRLoader in a worker thread;
 * the worker is terminated after `timeoutMs` or when `signal` aborts (then this rejects with the
 * signal's reason).
 */
export async function parseExrInWorker(buffer: ArrayBuffer, timeoutMs: number, signal?: AbortSignal): Promise<WorkerParse> {
  if (!isNodeRuntime()) return { unavailable: 'not Node.js' };
  const url = await resolveLoaderUrl();
  if (url === undefined) return { unavailable: 'three/examples/jsm/loaders/EXRLoader.js not found from this package' };
  let worker: NodeWorker;
  try {
    const { Worker } = await nodeModule<{ Worker: new (source: string, options: object) => NodeWorker }>('node:worker_threads');
    worker = new Worker(SOURCE, { eval: true, workerData: { buffer, loaderUrl: url }, transferList: [buffer], stdout: false, stderr: false });
  } catch (error) {
    return { unavailable: `no worker thread (${(error as Error).message})` };
  }
  return new Promise<WorkerParse>((resolve, reject) => {
    let settled = false;
    const settle = (result: WorkerParse | { abort: unknown }): void => {
      if (settled) return;
      settled = true;
      clearTimeout(timer);
      signal?.removeEventListener('abort', onAbort);
      void worker.terminate();
      if ('abort' in result) reject(result.abort);
      else resolve(result);
    };
    const timer = setTimeout(() => settle({ timedOut: true }), timeoutMs);
    const onAbort = (): void => settle({ abort: signal!.reason });
    signal?.addEventListener('abort', onAbort, { once: true });
    worker.on('message', (message) => settle(message));
    worker.on('error', (error) => settle({ error: error.message }));
    worker.on('exit', (code) => settle({ error: `the decoder thread exited (${code})` }));
  });
}
