// Shared fixtures for the GPU lighting tests: test HDRIs, the lights heap and uniforms of
// buildGpuLighting uploaded as the bindings the lighting WGSL reads, and quadrature of maps.
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

/** The map's texels as the `environmentMap` option takes them. */
export function mapOption(map: EnvironmentMap): { width: number; height: number; data: Float32Array; intensity: number; rotationRadians: number } {
  return { width: map.width, height: map.height, data: map.data, intensity: map.intensity, rotationRadians: map.rotationRadians };
}
