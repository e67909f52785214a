import { defineStructLayout, writeStruct, type StructLayout } from '../gpu-layout/struct-layout.ts';
import type { EnvironmentSampler } from './environment-sampling.ts';
import { sunLightLayout, type SunLight } from './sun-light.ts';

/**
 * A standalone packing of an environment for GPU code outside the path tracer (the path tracer
 * packs its own: gpu-lighting.ts puts the tables into the lights heap and the sun into
 * LightingUniforms):
 * - radiance: the map's RGBA float32 texels (row-major, row 0 = zenith): an rgba32float texture
 *   (textureLoad + hand-written bilinear: wrap u, clamp v) or `array<vec4f>`;
 * - entries: `array<EnvironmentAliasEntry>` (environment-sampling.ts: H marginal records, then W
 *   conditional records per row);
 * - uniforms: `EnvironmentMapUniforms` below;
 * - sun: `SunLight` (sun-light.ts), with `enabled` in these uniforms.
 */
export const environmentMapUniformsLayout: StructLayout = defineStructLayout('EnvironmentMapUniforms', 1, [
  ['width', 'u32'],
  ['height', 'u32'],
  ['intensity', 'f32', 'radiance multiplier'],
  ['rotationTurns', 'f32', 'rotationRadians / (2 pi), added to u'],
  ['sampleable', 'u32', '0: black map, no environment light samples'],
  ['sunEnabled', 'u32', '1: the SunLight uniform holds a sun disc'],
  ['reserved0', 'u32', 'pads the uniform block to 32 bytes'],
  ['reserved1', 'u32'],
]);

export interface PackedEnvironment {
  radiance: Float32Array;
  entries: ArrayBuffer;
  uniforms: ArrayBuffer;
  sun: ArrayBuffer;
}

export function packEnvironment(sampler: EnvironmentSampler, sun: SunLight | null = null): PackedEnvironment {
  const uniforms = new ArrayBuffer(environmentMapUniformsLayout.size);
  writeStruct(environmentMapUniformsLayout, new DataView(uniforms), 0, {
    width: sampler.map.width,
    height: sampler.map.height,
    intensity: sampler.map.intensity,
    rotationTurns: sampler.map.rotationRadians / (2 * Math.PI),
    sampleable: sampler.weightIntegral > 0 ? 1 : 0,
    sunEnabled: sun ? 1 : 0,
  });
  const sunBuffer = new ArrayBuffer(sunLightLayout.size);
  if (sun) {
    writeStruct(sunLightLayout, new DataView(sunBuffer), 0, {
      direction: sun.direction,
      oneMinusCosThetaMax: sun.oneMinusCosThetaMax,
      radiance: sun.radiance,
      limbDarkening: sun.limbDarkening ? 1 : 0,
    });
  }
  return { radiance: sampler.map.data, entries: sampler.entries, uniforms, sun: sunBuffer };
}
