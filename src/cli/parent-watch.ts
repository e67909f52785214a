/**
 * The rendering child process ends when the CLI process that started it dies, however it dies
 * (`kill -9` included, which leaves the parent no chance to stop it). Two signs, whichever comes
 * first: the IPC channel to the parent disconnects (the kernel closes its socket when the parent
 * dies; seen at once while the event loop runs), and the parent process id changes (a dead
 * parent's children are re-parented to init or a subreaper), polled on a worker thread so that it
 * is seen even while the main thread is busy in a long synchronous call (a pipeline compiling).
 * The main thread is asked to exit first; if it has not after `graceMs`, the watcher kills the
 * process.
 */
import { Worker } from 'node:worker_threads';

export interface ParentWatchOptions {
  /** How often the worker thread reads the parent process id. */
  pollMs?: number;
  /** How long the main thread has to exit before the process is killed. */
  graceMs?: number;
}

// JavaScript run by the worker thread (eval: no file to resolve in the built package), read as a
// script or a module alike (the process may run with --input-type=module), hence getBuiltinModule.
const watcherSource = `
const { parentPort, workerData } = process.getBuiltinModule('node:worker_threads');
const { ppid, pollMs, graceMs } = workerData;
const timer = setInterval(() => {
  if (process.ppid === ppid) return;
  clearInterval(timer);
  parentPort.postMessage('parent-gone');
  setTimeout(() => process.kill(process.pid, 'SIGKILL'), graceMs);
}, pollMs);
`;

/** Calls `onParentGone` (which should end the process) once this process's parent has died. */
export function watchParent(onParentGone: () => void, options: ParentWatchOptions = {}): void {
  let gone = false;
  const once = (): void => {
    if (gone) return;
    gone = true;
    onParentGone();
  };
  if (process.channel !== undefined) {
    process.once('disconnect', once);
    // The channel is only a sign of life: it must not keep the process running on its own.
    process.channel.unref();
  }
  const worker = new Worker(watcherSource, { eval: true, workerData: { ppid: process.ppid, pollMs: options.pollMs ?? 250, graceMs: options.graceMs ?? 1000 } });
  worker.on('message', once);
  worker.unref();
}
