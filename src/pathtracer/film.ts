import { readGpuBuffer } from './gpu-buffers.ts';
import type { WavefrontRadianceImage } from './types.ts';

/**
 * Reads of the film: the accumulation holds radiance sums with the sample count in alpha, the AOV
 * film holds sums of (albedo, depth) and (normal, hits) per pixel; readers divide by the count.
 */
export async function readMeanRadiance(device: GPUDevice, film: GPUBuffer, width: number, height: number): Promise<WavefrontRadianceImage> {
  const raw = new Float32Array(await readGpuBuffer(device, film, width * height * 16));
  const data = new Float32Array(width * height * 4);
  for (let i = 0; i < width * height; i++) {
    const n = raw[4 * i + 3]!;
    const inv = n > 0 ? 1 / n : 0;
    data[4 * i] = raw[4 * i]! * inv;
    data[4 * i + 1] = raw[4 * i + 1]! * inv;
    data[4 * i + 2] = raw[4 * i + 2]! * inv;
    data[4 * i + 3] = 1;
  }
  return { width, height, data };
}

export type AovName = 'albedo' | 'normal' | 'depth';

export async function readMeanAov(device: GPUDevice, film: GPUBuffer, aovs: GPUBuffer, name: AovName, width: number, height: number): Promise<WavefrontRadianceImage> {
  const pixels = width * height;
  const counts = new Float32Array(await readGpuBuffer(device, film, pixels * 16));
  const raw = new Float32Array(await readGpuBuffer(device, aovs, pixels * 32));
  const data = new Float32Array(pixels * 4);
  for (let i = 0; i < pixels; i++) {
    const n = counts[4 * i + 3]!;
    const inv = n > 0 ? 1 / n : 0;
    const o = 8 * i;
    if (name === 'albedo') data.set([raw[o]! * inv, raw[o + 1]! * inv, raw[o + 2]! * inv, 1], 4 * i);
    else if (name === 'depth') data.set([raw[o + 3]! * inv, 0, 0, 1], 4 * i);
    else data.set([raw[o + 4]! * inv, raw[o + 5]! * inv, raw[o + 6]! * inv, 1], 4 * i);
  }
  return { width, height, data };
}
