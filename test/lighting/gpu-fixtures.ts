// Shared fixtures for the GPU lighting tests: test HDRIs, the lights heap and uniforms of
// buildGpuLighting uploaded as the bindings the lighting WGSL reads, and quadrature of maps.
import assert from 'node:assert/strict';
import { buildGpuLighting, type GpuLighting, type GpuLightingInput } from '../../src/lighting/gpu-lighting.ts';
import type { LightingConfig } from '../../src/lighting/lighting-options.ts';
import { environmentRadiance, type EnvironmentMap } from '../../src/lighting/environment-map.ts';
import { equirectUvToDirection } from '../../src/lighting/equirect.ts';
import { uploadEnvironmentTexture } from '../../src/lighting/upload-environment.ts';
import { frameUniformsLayout } from '../../src/gpu-layout/records.ts';
import { writeStruct } from '../../src/gpu-layout/struct-layout.ts';
import { BufferUsage } from '../../src/gpu/webgpu-constants.ts';
import { uploadBuffer } from '../helpers/gpu.ts';
import type { TestResource } from '../helpers/wgsl.ts';
import { makeMap } from './helpers.ts';

/**
 * A small HDRI: a sky gradient varying in azimuth, a darker ground, and a 2 x 2 texel "sun" 1000
 * times brighter than the sky (the case importance sampling exists for).
 */
export function testHdri(width = 64, height = 32, sunRadiance = 400): EnvironmentMap {
  return makeMap(width, height, (i, j) => {
    const u = (i + 0.5) / width;
    const v = (j + 0.5) / height;
    const sun = i >= Math.floor(0.62 * width) && i < Math.floor(0.62 * width) + 2 && j >= Math.floor(0.25 * height) && j < Math.floor(0.25 * height) + 2;
    if (sun) return [sunRadiance, 0.9 * sunRadiance, 0.75 * sunRadiance];
    const az = 1 + 0.4 * Math.cos(2 * Math.PI * u);
    if (v > 0.5) return [0.15 * az, 0.12 * az, 0.1 * az];
    const up = 1 - 2 * v;
    return [(0.3 + 0.5 * up) * az, (0.4 + 0.4 * up) * az, (0.6 + 0.3 * up) * az];
  });
}

export const noLights: Omit<LightingConfig, 'environment'> = { punctual: [], area: [], portals: [], portalMode: 'guide', lightSampler: 'auto', environmentSampling: 'importance' };

export function lightingFor(config: Partial<LightingConfig>, extra: Partial<GpuLightingInput> = {}): GpuLighting {
  return buildGpuLighting({
    config: { environment: { kind: 'none' }, ...noLights, ...config },
    triangles: { records: new ArrayBuffer(112), count: 0 },
    sceneCenter: [0, 0, 0],
    sceneRadius: 1,
    ...extra,
  });
}

/** The bindings the lighting WGSL reads (lights heap, lighting and frame uniforms, environment texture). */
export function lightingResources(device: GPUDevice, lighting: GpuLighting): Record<string, TestResource> {
  const frame = new ArrayBuffer(frameUniformsLayout.size);
  writeStruct(frameUniformsLayout, new DataView(frame), 0, {
    environmentRadiance: lighting.uniformEnvironment,
    environmentSelectProbability: lighting.environmentSelectProbability,
    lightCount: lighting.boundedCount,
  });
  return {
    lights: uploadBuffer(device, lighting.heap),
    lighting: uploadBuffer(device, lighting.uniforms, BufferUsage.UNIFORM),
    frame: uploadBuffer(device, frame, BufferUsage.UNIFORM),
    environmentTexture: uploadEnvironmentTexture(device, lighting.environmentMap).view,
  };
}

/**
 * Irradiance on surfaces with normals `normals` (xyz triples) from the map's bilinear radiance,
 * by the midpoint rule on `sub` x `sub` points per texel (d omega = 2 pi^2 sin(theta) du dv).
 */
export function mapIrradiance(map: EnvironmentMap, normals: Float64Array, sub = 4): Float64Array {
  const w = map.width * sub;
  const h = map.height * sub;
  const n = normals.length / 3;
  const e = new Float64Array(3 * n);
  for (let j = 0; j < h; j++) {
    const v = (j + 0.5) / h;
    const weight = (2 * Math.PI * Math.PI * Math.sin(Math.PI * v)) / (w * h);
    for (let i = 0; i < w; i++) {
      const d = equirectUvToDirection((i + 0.5) / w, v, map.rotationRadians);
      const L = environmentRadiance(map, d);
      for (let k = 0; k < n; k++) {
        const c = normals[3 * k]! * d[0] + normals[3 * k + 1]! * d[1] + normals[3 * k + 2]! * d[2];
        if (c <= 0) continue;
        const f = c * weight;
        e[3 * k] += L[0] * f;
        e[3 * k + 1] += L[1] * f;
        e[3 * k + 2] += L[2] * f;
      }
    }
  }
  return e;
}

/**
 * A Lambertian unit sphere at the origin of albedo `albedo`, seen by an orthographic camera looking
 * down -Z with view height 2 `half` in a `size` x `size` image, under `map` alone: every pixel wholly
 * on the sphere must be albedo / pi x the irradiance at its normals (the mean over 4 x 4 points of
 * the pixel, from CPU quadrature of the map): over the whole disk within `meanTolerance`, over each
 * 16 x 16 pixel block within `blockTolerance` (relative).
 */
export function assertSphereMatchesIrradiance(
  image: Float32Array,
  map: EnvironmentMap,
  o: { size: number; half: number; albedo: number; meanTolerance: number; blockTolerance: number },
): void {
  const { size, half } = o;
  const SUB = 4;
  const pixels: number[] = [];
  const normals: number[] = [];
  for (let y = 0; y < size; y++) {
    for (let x = 0; x < size; x++) {
      const corners = [0, 1].flatMap((a) => [0, 1].map((b) => [((x + a) / size) * 2 * half - half, half - ((y + b) / size) * 2 * half]));
      if (!corners.every(([px, py]) => px! * px! + py! * py! < 0.95)) continue;
      pixels.push(y * size + x);
      for (let k = 0; k < SUB * SUB; k++) {
        const px = ((x + ((k % SUB) + 0.5) / SUB) / size) * 2 * half - half;
        const py = half - ((y + (Math.floor(k / SUB) + 0.5) / SUB) / size) * 2 * half;
        normals.push(px, py, Math.sqrt(1 - px * px - py * py));
      }
    }
  }
  const e = mapIrradiance(map, Float64Array.from(normals), 2);
  let got = 0;
  let want = 0;
  const blocks = new Map<number, { got: number; want: number }>();
  pixels.forEach((p, k) => {
    for (let c = 0; c < 3; c++) {
      let expect = 0;
      for (let q = 0; q < SUB * SUB; q++) expect += ((o.albedo / Math.PI) * e[3 * (SUB * SUB * k + q) + c]!) / (SUB * SUB);
      got += image[4 * p + c]!;
      want += expect;
      const key = 100 * Math.floor((p % size) / 16) + Math.floor(p / size / 16);
      const b = blocks.get(key) ?? { got: 0, want: 0 };
      b.got += image[4 * p + c]!;
      b.want += expect;
      blocks.set(key, b);
    }
  });
  assert.ok(pixels.length > 400);
  assert.ok(Math.abs(got - want) < o.meanTolerance * want, `mean over the sphere: ${got / pixels.length / 3} vs ${want / pixels.length / 3}`);
  for (const [key, b] of blocks) assert.ok(Math.abs(b.got - b.want) < o.blockTolerance * b.want, `block ${key}: ${b.got} vs ${b.want}`);
}

/** The map's texels as the `environmentMap` option takes them. */
export function mapOption(map: EnvironmentMap): { width: number; height: number; data: Float32Array; intensity: number; rotationRadians: number } {
  return { width: map.width, height: map.height, data: map.data, intensity: map.intensity, rotationRadians: map.rotationRadians };
}
