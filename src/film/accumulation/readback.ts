import { adaptiveListSlots } from '../../gpu-layout/constants.ts';
import { filmAovPixelLayout, filmMomentsLayout, filmPixelLayout } from '../../gpu-layout/records.ts';
import { fieldOf, type StructLayout } from '../../gpu-layout/struct-layout.ts';
import { luminance } from '../../lighting/emissive-lights.ts';
import type { WavefrontAovName } from '../aovs.ts';
import { readGpuBuffer } from '../../gpu/read-buffer.ts';

/**
 * Reads of the film. Its records (FilmPixel, FilmAovPixel, FilmMoments in gpu-layout/records.ts)
 * hold sums over each pixel's samples; readers divide by the sample count. The id film holds
 * 1 + the instance index of the pixel's first sample that reached a non-specular surface.
 */

/** Linear radiance read from the film: RGBA float32, row-major, top row first. */
export interface WavefrontRadianceImage {
  width: number;
  height: number;
  /** RGBA, linear mean radiance, row-major, top row first. */
  data: Float32Array;
}

/** Where a record's fields start in a float32 view of an array of it, and the record's stride. */
export interface FloatFields<Name extends string> {
  readonly stride: number;
  readonly at: Readonly<Record<Name, number>>;
}

export function floatFields<Name extends string>(layout: StructLayout, names: readonly Name[]): FloatFields<Name> {
  const at = Object.fromEntries(names.map((n) => [n, fieldOf(layout, n).offset / 4])) as Record<Name, number>;
  return { stride: layout.size / 4, at };
}

const pixelFields = floatFields(filmPixelLayout, ['radiance', 'samples']);
const aovFields = floatFields(filmAovPixelLayout, ['albedo', 'depth', 'normal', 'hits', 'emission', 'reflectedLuminanceSquared']);
const momentFields = floatFields(filmMomentsLayout, ['radianceSquared']);

/** The film's radiance sums and sample counts, read back. */
async function readFilmPixels(device: GPUDevice, film: GPUBuffer, pixels: number): Promise<{ radiance(i: number, c: number): number; samples(i: number): number }> {
  const raw = new Float32Array(await readGpuBuffer(device, film, pixels * filmPixelLayout.size));
  const { stride, at } = pixelFields;
  return { radiance: (i, c) => raw[stride * i + at.radiance + c]!, samples: (i) => raw[stride * i + at.samples]! };
}

export async function readMeanRadiance(device: GPUDevice, film: GPUBuffer, width: number, height: number): Promise<WavefrontRadianceImage> {
  const pixels = width * height;
  const f = await readFilmPixels(device, film, pixels);
  const data = new Float32Array(pixels * 4);
  for (let i = 0; i < pixels; i++) {
    const n = f.samples(i);
    const inv = n > 0 ? 1 / n : 0;
    data[4 * i] = f.radiance(i, 0) * inv;
    data[4 * i + 1] = f.radiance(i, 1) * inv;
    data[4 * i + 2] = f.radiance(i, 2) * inv;
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
  const film = await readFilmPixels(device, buffers.film, pixels);
  const data = new Float32Array(pixels * 4);
  if (name === 'sampleCount') {
    for (let i = 0; i < pixels; i++) data.set([film.samples(i), 0, 0, 1], 4 * i);
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
  const aovs = new Float32Array(await readGpuBuffer(device, buffers.aovs, pixels * filmAovPixelLayout.size));
  const { stride, at } = aovFields;
  const aov = (i: number, field: keyof typeof at, c = 0): number => aovs[stride * i + at[field] + c]!;
  if (name === 'variance') {
    const moments = new Float32Array(await readGpuBuffer(device, buffers.moments, pixels * filmMomentsLayout.size));
    const m = momentFields;
    for (let i = 0; i < pixels; i++) {
      const n = film.samples(i);
      const sum = [0, 1, 2].map((c) => film.radiance(i, c));
      const sum2 = [0, 1, 2].map((c) => moments[m.stride * i + m.at.radianceSquared + c]!);
      data.set([0, 1, 2].map((c) => varianceOfMean(sum[c]!, sum2[c]!, n)), 4 * i);
      // Luminance is linear, so the luminance of a sum is the sum of the luminances.
      const reflected = sum.map((v, c) => v - aov(i, 'emission', c));
      data[4 * i + 3] = varianceOfMean(luminance(reflected), aov(i, 'reflectedLuminanceSquared'), n);
    }
    return { width, height, data };
  }
  for (let i = 0; i < pixels; i++) {
    const n = film.samples(i);
    const inv = n > 0 ? 1 / n : 0;
    const coverage = aov(i, 'hits') * inv;
    const mean = (field: 'albedo' | 'normal' | 'emission'): number[] => [0, 1, 2].map((c) => aov(i, field, c) * inv);
    if (name === 'albedo') data.set([...mean('albedo'), coverage], 4 * i);
    else if (name === 'depth') data.set([aov(i, 'depth') * inv, 0, 0, coverage], 4 * i);
    else if (name === 'normal') data.set([...mean('normal'), coverage], 4 * i);
    else data.set([...mean('emission'), coverage], 4 * i);
  }
  return { width, height, data };
}
