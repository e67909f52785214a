import { adaptiveListSlots } from '../../gpu-layout/constants.ts';
import { luminance } from '../../lighting/emissive-lights.ts';
import type { WavefrontAovName } from '../aovs.ts';
import { readGpuBuffer } from '../../pathtracer/gpu-buffers.ts';
import type { WavefrontRadianceImage } from '../../pathtracer/types.ts';

/**
 * Reads of the film: the accumulation holds radiance sums with the sample count in alpha; the AOV
 * film sums of (albedo, depth), (normal, hits) and (emission, squared luminance of the radiance
 * without it) per pixel; the moments film the sum of the
 * even-indexed samples with their count, and the sums of squared radiance and squared luminance; the
 * id film 1 + the instance index of the pixel's first sample that reached a non-specular surface.
 * Readers divide by the sample count.
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

/** Reads RGBA float32 pixels stored as (rgb, 1) (the denoiser's output). */
export async function readRgbaImage(device: GPUDevice, buffer: GPUBuffer, width: number, height: number): Promise<WavefrontRadianceImage> {
  return { width, height, data: new Float32Array(await readGpuBuffer(device, buffer, width * height * 16)) };
}

/** @deprecated Use WavefrontAovName. */
export type AovName = WavefrontAovName;

export interface FilmBuffers {
  film: GPUBuffer;
  aovs: GPUBuffer;
  moments: GPUBuffer;
  ids: GPUBuffer;
  /** Adaptive sampling's per-pixel error and active list; null when it is off. */
  adaptive: { error: GPUBuffer; pixels: GPUBuffer } | null;
}

/** Object id and material index of every instance (the id AOVs map instance indices through these). */
export interface InstanceIds {
  objectIds: Int32Array;
  materialIds: Int32Array;
}

/**
 * Unbiased variance of the mean of n samples from their sum and sum of squares:
 * (sum2 - sum^2 / n) / ((n - 1) n); +Infinity below two samples (unknown), never negative.
 */
export function varianceOfMean(sum: number, sum2: number, n: number): number {
  if (!(n >= 2)) return Infinity;
  return Math.max(sum2 - (sum * sum) / n, 0) / ((n - 1) * n);
}

/**
 * One AOV as RGBA float32, top row first (see WavefrontPathTracingRenderer.readAov for what each
 * channel holds).
 */
export async function readAovImage(device: GPUDevice, buffers: FilmBuffers, name: WavefrontAovName, width: number, height: number, ids: InstanceIds): Promise<WavefrontRadianceImage> {
  const pixels = width * height;
  const counts = new Float32Array(await readGpuBuffer(device, buffers.film, pixels * 16));
  const data = new Float32Array(pixels * 4);
  if (name === 'sampleCount') {
    for (let i = 0; i < pixels; i++) data.set([counts[4 * i + 3]!, 0, 0, 1], 4 * i);
    if (buffers.adaptive) {
      // g: the error of the last convergence test (F32 max below the minimum samples); b: 1 while sampling.
      const error = new Float32Array(await readGpuBuffer(device, buffers.adaptive.error, pixels * 4));
      const list = new Uint32Array(await readGpuBuffer(device, buffers.adaptive.pixels, (adaptiveListSlots.listStart + pixels) * 4));
      for (let i = 0; i < pixels; i++) data[4 * i + 1] = error[i]!;
      const active = list[adaptiveListSlots.activeCount]!;
      for (let k = 0; k < active; k++) data[4 * list[adaptiveListSlots.listStart + k]! + 2] = 1;
    }
    return { width, height, data };
  }
  if (name === 'objectId' || name === 'materialId') {
    const raw = new Uint32Array(await readGpuBuffer(device, buffers.ids, pixels * 4));
    const table = name === 'objectId' ? ids.objectIds : ids.materialIds;
    for (let i = 0; i < pixels; i++) data.set([raw[i]! === 0 ? -1 : table[raw[i]! - 1]!, 0, 0, 1], 4 * i);
    return { width, height, data };
  }
  const aovs = new Float32Array(await readGpuBuffer(device, buffers.aovs, pixels * 48));
  if (name === 'variance') {
    const raw = new Float32Array(await readGpuBuffer(device, buffers.moments, pixels * 32));
    for (let i = 0; i < pixels; i++) {
      const n = counts[4 * i + 3]!;
      const sum = [counts[4 * i]!, counts[4 * i + 1]!, counts[4 * i + 2]!];
      const sum2 = [raw[8 * i + 4]!, raw[8 * i + 5]!, raw[8 * i + 6]!];
      data.set([0, 1, 2].map((c) => varianceOfMean(sum[c]!, sum2[c]!, n)), 4 * i);
      // Luminance is linear, so the luminance of a sum is the sum of the luminances.
      const reflected = sum.map((v, c) => v - aovs[12 * i + 8 + c]!);
      data[4 * i + 3] = varianceOfMean(luminance(reflected), aovs[12 * i + 11]!, n);
    }
    return { width, height, data };
  }
  for (let i = 0; i < pixels; i++) {
    const n = counts[4 * i + 3]!;
    const inv = n > 0 ? 1 / n : 0;
    const o = 12 * i;
    const coverage = aovs[o + 7]! * inv;
    if (name === 'albedo') data.set([aovs[o]! * inv, aovs[o + 1]! * inv, aovs[o + 2]! * inv, coverage], 4 * i);
    else if (name === 'depth') data.set([aovs[o + 3]! * inv, 0, 0, coverage], 4 * i);
    else if (name === 'normal') data.set([aovs[o + 4]! * inv, aovs[o + 5]! * inv, aovs[o + 6]! * inv, coverage], 4 * i);
    else data.set([aovs[o + 8]! * inv, aovs[o + 9]! * inv, aovs[o + 10]! * inv, coverage], 4 * i);
  }
  return { width, height, data };
}
