import { queueBufferWords } from '../gpu-layout/constants.ts';
import { pathRecordLayout } from '../gpu-layout/records.ts';

/**
 * Paths per wave when the caller does not set tileSize: enough to fill a discrete GPU (an H100
 * keeps about 270k invocations resident; a wave of 2^21 paths gives each bounce's dispatches
 * several rounds of work), bounded by 512 MiB of path records.
 */
export const defaultMaxWavePaths = 2 ** 21;

/** Bytes the wave keeps per path: its record and three queue entries (two ray queues, one shadow queue). */
export const bytesPerWavePath = pathRecordLayout.size + 3 * 4;

/** The most paths one wave of this device can hold: what one storage binding holds of path records. */
export function deviceWavePaths(limits: Pick<GPUSupportedLimits, 'maxStorageBufferBindingSize' | 'maxBufferSize'>, budget = defaultMaxWavePaths): number {
  const binding = Math.min(limits.maxStorageBufferBindingSize, limits.maxBufferSize);
  let paths = Math.min(budget, Math.floor(binding / pathRecordLayout.size));
  while (paths > 1 && queueBufferWords(paths) * 4 > binding) paths -= 1;
  return Math.max(1, paths);
}

/**
 * The most paths a wave may hold: tileSize^2 when the caller sets tileSize (their bound on queue
 * memory; checked against the device like any buffer), else what the device holds.
 */
export function waveBound(deviceMaximum: number, tileSize: number | null): number {
  return tileSize !== null ? tileSize * tileSize : deviceMaximum;
}

/**
 * Workgroups of a grid-stride dispatch (the traversal kernel loops over its queues). On a GPU,
 * enough to keep every core busy with several workgroups in flight (8192 x 64 invocations, twice
 * what an H100 holds resident); the loop takes the rest. On a CPU adapter (lavapipe, SwiftShader)
 * every workgroup is a task of its thread pool, so a few per thread.
 */
export function gridWorkgroupLimit(softwareAdapter: boolean, limits: Pick<GPUSupportedLimits, 'maxComputeWorkgroupsPerDimension'>): number {
  return Math.min(softwareAdapter ? 64 : 8192, limits.maxComputeWorkgroupsPerDimension);
}
