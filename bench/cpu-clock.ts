/**
 * CPU time of the threads other than the JavaScript main thread, around a timed frame. On a CPU
 * implementation of WebGPU (Mesa lavapipe/llvmpipe) the shader work runs on the driver's threads in
 * this process, so this is the work a frame costs, and it is far less sensitive than wall clock to
 * other processes competing for the cores: a busy machine stretches the wall time, not the work.
 * The main thread is left out because it spends the frame polling for the GPU to finish, which
 * takes whatever CPU it is given. Meaningless on a real GPU (the work is not on the CPU there).
 */

export interface CpuMark {
  wallMs: number;
  /** user + system of the whole process, µs */
  processCpuUs: number;
  /** user + system of the calling (main) thread, µs */
  mainThreadCpuUs: number;
}

export function cpuMark(wallMs = performance.now()): CpuMark {
  const p = process.cpuUsage();
  const t = process.threadCpuUsage();
  return { wallMs, processCpuUs: p.user + p.system, mainThreadCpuUs: t.user + t.system };
}

/** CPU seconds spent off the main thread between two marks. */
export function workerCpuSeconds(from: CpuMark, to: CpuMark): number {
  return (to.processCpuUs - from.processCpuUs - (to.mainThreadCpuUs - from.mainThreadCpuUs)) / 1e6;
}

/** Adapters whose "GPU" work runs on this machine's CPU, where workerCpuSeconds means something. */
export function isCpuAdapter(adapter: string | null | undefined): boolean {
  return adapter != null && /llvmpipe|lavapipe|swiftshader|software/i.test(adapter);
}

/**
 * For harnesses that do not report worker CPU time themselves (those before it existed): find the
 * timed frame among the marks that performance.now() left, as the pair of calls whose interval
 * equals the reported `seconds` (within `tolerance`, e.g. 0.0005 for seconds rounded to ms) and
 * starts after `notBefore`. A frame timed by the harness encloses the renderer's own timing of
 * the same frame, so a candidate enclosing another candidate wins; otherwise the earliest one.
 * Returns the mark indices, or null when nothing matches.
 */
export function findTimedInterval(marks: readonly CpuMark[], seconds: number, tolerance: number, notBefore = 0): [number, number] | null {
  const candidates: Array<[number, number]> = [];
  for (let j = notBefore + 1; j < marks.length; j++) {
    for (let i = notBefore; i < j; i++) {
      if (Math.abs((marks[j]!.wallMs - marks[i]!.wallMs) / 1000 - seconds) <= tolerance) candidates.push([i, j]);
    }
  }
  if (candidates.length === 0) return null;
  const enclosing = candidates.find(([i, j]) => candidates.some(([k, l]) => k > i && l < j));
  return enclosing ?? candidates[0]!;
}
