/**
 * CPU time of the threads other than the JavaScript main thread, around a timed frame. On a CPU
 * implementation of WebGPU (Mesa lavapipe/llvmpipe) the shader work runs on the driver's threads in
 * this process, so this is the work a frame costs, and it is far less sensitive than wall clock to
 * other processes competing for the cores: a busy machine stretches the wall time, not the work.
 * The main thread is left out because it spends the frame polling for the GPU to finish, which
 * takes whatever CPU it is given. Meaningless on a real GPU (the work is not on the CPU there).
 *
 * Each mark also reads the machine's busy time (Linux /proc/stat, including steal time from the
 * hypervisor), so the load of *other* processes during a frame can be shown beside the figures.
 */
import { readFileSync } from 'node:fs';

export interface CpuMark {
  wallMs: number;
  /** user + system of the whole process, µs */
  processCpuUs: number;
  /** user + system of the calling (main) thread, µs */
  mainThreadCpuUs: number;
  /** Busy time of all the machine's cores, µs (10 ms resolution); null where /proc/stat is absent. */
  machineBusyUs: number | null;
}

/** USER_HZ: the unit of /proc/stat, 100 on every mainstream Linux architecture. */
const USER_HZ = 100;
let procStatReadable = true;

/** user + nice + system + irq + softirq + steal of the `cpu` line of /proc/stat, µs. */
function machineBusyUs(): number | null {
  if (!procStatReadable) return null;
  try {
    const line = readFileSync('/proc/stat', 'latin1').slice(0, 256).split('\n', 1)[0]!;
    const [user, nice, system, , , irq, softirq, steal] = line.trim().split(/\s+/).slice(1).map(Number);
    return ((user! + nice! + system! + irq! + softirq! + (steal ?? 0)) * 1e6) / USER_HZ;
  } catch {
    procStatReadable = false;
    return null;
  }
}

export function cpuMark(wallMs = performance.now()): CpuMark {
  const p = process.cpuUsage();
  const t = process.threadCpuUsage();
  return { wallMs, processCpuUs: p.user + p.system, mainThreadCpuUs: t.user + t.system, machineBusyUs: machineBusyUs() };
}

/**
 * Cores' worth of CPU that other processes (and the hypervisor, as steal) took between two marks:
 * the machine's busy time minus this process's, over the wall time. Null without /proc/stat.
 * Its resolution is 10 ms of CPU, i.e. about 0.01 core over a frame of a few seconds.
 */
export function otherLoadCores(from: CpuMark, to: CpuMark): number | null {
  if (from.machineBusyUs === null || to.machineBusyUs === null || to.wallMs <= from.wallMs) return null;
  const others = to.machineBusyUs - from.machineBusyUs - (to.processCpuUs - from.processCpuUs);
  return others / 1e6 / ((to.wallMs - from.wallMs) / 1000);
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
 * timed frame among the marks that performance.now() left, as a pair of calls, starting at or after
 * `notBefore`, whose interval equals the reported `seconds` (within `tolerance`, e.g. 0.0005 for
 * seconds rounded to ms). Time-sliced work (the asynchronous BVH build checks the clock every few
 * thousand steps) leaves thousands of marks, so some of their pairs match any duration by chance;
 * the timed frame is the matching pair with the fewest marks inside it (a frame is one await of
 * renderFrame, which reads the clock only at its start and end), then the one with the most worker
 * CPU. Returns the mark indices, or null when nothing matches.
 */
export function findTimedInterval(marks: readonly CpuMark[], seconds: number, tolerance: number, notBefore = 0): [number, number] | null {
  let best: { i: number; j: number; inside: number; cpu: number } | null = null;
  for (let i = notBefore; i < marks.length; i++) {
    const lo = marks[i]!.wallMs + (seconds - tolerance) * 1000;
    const hi = marks[i]!.wallMs + (seconds + tolerance) * 1000;
    // Marks are in time order: binary search for the first one at or after `lo`.
    let a = i + 1, b = marks.length;
    while (a < b) {
      const mid = (a + b) >> 1;
      if (marks[mid]!.wallMs < lo) a = mid + 1;
      else b = mid;
    }
    for (let j = a; j < marks.length && marks[j]!.wallMs <= hi; j++) {
      const inside = j - i - 1;
      const cpu = workerCpuSeconds(marks[i]!, marks[j]!);
      if (!best || inside < best.inside || (inside === best.inside && cpu > best.cpu)) best = { i, j, inside, cpu };
    }
  }
  return best ? [best.i, best.j] : null;
}
