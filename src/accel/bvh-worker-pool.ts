/**
 * A lazily created pool of BVH build workers, in browsers (Web Workers) and Node (`worker_threads`).
 *
 * The workers are inline: their source is a string made of `bvhWorkerMain` and `createBvhKernels`
 * (`Function.prototype.toString`, both self-contained) behind a few lines that bind the host's
 * message port. No worker file has to be found at run time, so the same code works from the .ts
 * sources, from dist/esm and dist/cjs, and inside application bundles (Vite, esbuild, webpack, ...)
 * without plugins or `new URL(..., import.meta.url)` conventions:
 * - browsers (and Deno, Bun): `new Worker(URL.createObjectURL(new Blob([source])))`; a Content
 *   Security Policy must allow `worker-src blob:`;
 * - Node: `new Worker(source, { eval: true })` from `node:worker_threads`, imported through a
 *   variable specifier so bundlers targeting browsers leave it alone.
 * When neither works (no Worker, CSP refusal, a tool that instruments function bodies), callers get
 * `null` or a rejected request and fall back to the single-threaded build. The WebAssembly module
 * (bvh-wasm.ts) is compiled here and posted to the workers; under a CSP without 'wasm-unsafe-eval'
 * everything runs in JS (the same tree), or pass `wasm: false` to skip the attempt.
 *
 * Workers are kept for later builds (starting one costs tens of milliseconds). In Node they are
 * `unref`ed while idle, so they never keep a process alive; `terminateBvhWorkers` ends them.
 */
import { isNodeRuntime, nodeModule } from '../io/platform.ts';
import { createBvhKernels } from './bvh-kernels.ts';
import { bvhWorkerMain } from './bvh-worker-main.ts';

export interface BvhWorkerReply {
  id: number;
  error?: string;
  [key: string]: unknown;
}

interface PendingRequest {
  resolve(reply: BvhWorkerReply): void;
  reject(error: Error): void;
}

interface PooledWorker {
  post(message: unknown, transfer: Transferable[]): void;
  terminate(): void;
  /** Node: keep the process alive while requests are in flight. */
  setActive(active: boolean): void;
  pending: Map<number, PendingRequest>;
  dead: boolean;
}

export interface BvhWorkerPool {
  /** Whether workers can share this thread's memory (SharedArrayBuffer and Atomics). */
  readonly sharedMemory: boolean;
  size(): number;
  /** Sends one request to worker `index` and resolves with its reply (rejects on a worker error). */
  request(index: number, message: Record<string, unknown>, transfer?: Transferable[]): Promise<BvhWorkerReply>;
  /** Requests in flight on worker `index` (all builds together). */
  load(index: number): number;
}

type Spawn = (source: string, onMessage: (data: unknown) => void, onFailure: (error: Error) => void) => Omit<PooledWorker, 'pending' | 'dead'>;

const NODE_HOST = `const host = (() => {
  const { parentPort } = require('node:worker_threads');
  return { onMessage: (h) => parentPort.on('message', h), post: (m, t) => parentPort.postMessage(m, t) };
})();`;

const WEB_HOST = `const host = {
  onMessage: (h) => self.addEventListener('message', (e) => h(e.data)),
  post: (m, t) => self.postMessage(m, t),
};`;

/**
 * The worker's whole source. `__name` is the one helper a bundler may weave into function bodies
 * (esbuild's keepNames); a no-op stand-in keeps such a build working. Helpers of other tools (coverage
 * counters, say) make the worker fail to start, and the build falls back to the calling thread.
 */
function workerSource(hostPrologue: string): string {
  return `"use strict";\nconst __name = (target) => target;\n${hostPrologue}\n(${bvhWorkerMain.toString()})(${createBvhKernels.toString()}, host);\n`;
}

interface NodeWorker {
  on(event: 'message', h: (m: unknown) => void): void;
  on(event: 'error', h: (e: Error) => void): void;
  on(event: 'exit', h: (code: number) => void): void;
  postMessage(m: unknown, t?: readonly Transferable[]): void;
  terminate(): Promise<number>;
  ref(): void;
  unref(): void;
}

async function nodeSpawner(): Promise<Spawn | null> {
  if (!isNodeRuntime()) return null;
  let mod: { Worker: new (source: string, options: { eval: boolean }) => NodeWorker };
  try {
    mod = await nodeModule<typeof mod>('node:worker_threads');
  } catch {
    return null;
  }
  const source = workerSource(NODE_HOST);
  return (_source, onMessage, onFailure) => {
    const worker = new mod.Worker(source, { eval: true });
    worker.unref();
    worker.on('message', onMessage);
    worker.on('error', onFailure);
    worker.on('exit', (code) => onFailure(new Error(`bvh worker exited with code ${code}`)));
    return {
      post: (m, t) => worker.postMessage(m, t),
      terminate: () => void worker.terminate(),
      setActive: (active) => (active ? worker.ref() : worker.unref()),
    };
  };
}

function webSpawner(): Spawn | null {
  const g = globalThis as {
    Worker?: new (url: string, options?: { type?: 'classic' | 'module' }) => Worker;
    Blob?: typeof Blob;
    URL?: typeof URL;
  };
  if (typeof g.Worker !== 'function' || typeof g.Blob !== 'function' || typeof g.URL?.createObjectURL !== 'function') return null;
  const WorkerCtor = g.Worker;
  const url = g.URL.createObjectURL(new g.Blob([workerSource(WEB_HOST)], { type: 'text/javascript' }));
  return (_source, onMessage, onFailure) => {
    let worker: Worker;
    try {
      worker = new WorkerCtor(url);
    } catch {
      // Deno only runs module workers; the source is valid as either.
      worker = new WorkerCtor(url, { type: 'module' });
    }
    worker.addEventListener('message', (e) => onMessage(e.data));
    worker.addEventListener('error', (e) => onFailure(new Error(`bvh worker failed: ${e.message || 'could not start (Content Security Policy?)'}`)));
    worker.addEventListener('messageerror', () => onFailure(new Error('bvh worker: message could not be deserialized')));
    return { post: (m, t) => worker.postMessage(m, t), terminate: () => worker.terminate(), setActive: () => {} };
  };
}

let spawnerPromise: Promise<Spawn | null> | undefined;
let workers: PooledWorker[] = [];
let nextRequestId = 1;

function canShareMemory(): boolean {
  const g = globalThis as { crossOriginIsolated?: boolean };
  return typeof SharedArrayBuffer === 'function' && typeof Atomics === 'object' && g.crossOriginIsolated !== false;
}

function startWorker(spawn: Spawn): PooledWorker {
  const pending = new Map<number, PendingRequest>();
  const entry: PooledWorker = { post: () => {}, terminate: () => {}, setActive: () => {}, pending, dead: false };
  const fail = (error: Error): void => {
    if (entry.dead) return;
    entry.dead = true;
    workers = workers.filter((w) => w !== entry);
    for (const request of pending.values()) request.reject(error);
    pending.clear();
    entry.terminate();
  };
  const started = spawn('', (data) => {
    const reply = data as BvhWorkerReply;
    const request = pending.get(reply.id);
    if (!request) return;
    pending.delete(reply.id);
    if (pending.size === 0) entry.setActive(false);
    if (reply.error !== undefined) request.reject(new Error(`bvh worker: ${reply.error}`));
    else request.resolve(reply);
  }, fail);
  entry.post = started.post;
  entry.terminate = started.terminate;
  entry.setActive = started.setActive;
  return entry;
}

/**
 * A pool of at least `size` workers, or null where workers cannot be started here. Starting is
 * asynchronous (Node's module is imported on first use); a worker that fails later rejects its
 * requests and leaves the pool.
 */
export async function getBvhWorkerPool(size: number): Promise<BvhWorkerPool | null> {
  spawnerPromise ??= (async () => webSpawner() ?? (await nodeSpawner()))();
  const spawn = await spawnerPromise;
  if (!spawn) return null;
  try {
    while (workers.length < size) workers.push(startWorker(spawn));
  } catch {
    return null;
  }
  const members = workers.slice(0, size);
  return {
    sharedMemory: canShareMemory(),
    size: () => members.length,
    load: (index) => members[index]!.pending.size,
    request(index, message, transfer = []) {
      const worker = members[index]!;
      if (worker.dead) return Promise.reject(new Error('bvh worker is gone'));
      const id = nextRequestId++;
      return new Promise<BvhWorkerReply>((resolve, reject) => {
        worker.pending.set(id, { resolve, reject });
        if (worker.pending.size === 1) worker.setActive(true);
        try {
          worker.post({ ...message, id }, transfer);
        } catch (error) {
          worker.pending.delete(id);
          reject(error instanceof Error ? error : new Error(String(error)));
        }
      });
    },
  };
}

/**
 * Starts the BVH worker pool ahead of the first parallel build (a worker takes 50-200 ms to start)
 * and resolves once every worker answers; false where workers cannot run here. Optional: a build
 * starts the pool itself. A renderer can call this when it begins loading a large asset.
 */
export async function warmBvhWorkers(count = defaultBvhWorkerCount()): Promise<boolean> {
  const pool = await getBvhWorkerPool(count);
  if (!pool) return false;
  try {
    // `end` of a build no worker knows is a no-op round trip.
    await Promise.all(Array.from({ length: pool.size() }, (_, w) => pool.request(w, { op: 'end', build: 0 })));
    return true;
  } catch {
    return false;
  }
}

/** Default worker count: the hardware threads (navigator.hardwareConcurrency, in Node too), at most 8. */
export function defaultBvhWorkerCount(): number {
  const n = (globalThis as { navigator?: { hardwareConcurrency?: number } }).navigator?.hardwareConcurrency;
  return Math.max(1, Math.min(8, Number.isInteger(n) && n! > 0 ? n! : 2));
}

/** Ends every pooled BVH worker (a later parallel build starts new ones). */
export function terminateBvhWorkers(): void {
  const all = workers;
  workers = [];
  for (const w of all) {
    w.dead = true;
    for (const request of w.pending.values()) request.reject(new Error('bvh workers terminated'));
    w.pending.clear();
    w.terminate();
  }
}
