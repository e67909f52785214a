import { describe, fail } from '../errors/validate.ts';
import { maxCoordinateMagnitude, maxRadiance } from '../scene/limits.ts';
import type { WavefrontPunctualLightInput } from '../scene/types.ts';
import type { AreaLight } from './area-lights.ts';
import { validateEnvironmentMap, type EnvironmentMap, type EnvironmentMapInput } from './environment-map.ts';
import { createEnvironmentLighting, type EnvironmentLightingInput, type EnvironmentLightingPreset } from './environment-lighting.ts';
import type { WavefrontAreaLightInput } from './light-types.ts';
import { validateLights } from './lights.ts';
import { validateEnvironmentPortalMode, validateEnvironmentPortals, type EnvironmentPortalInput, type EnvironmentPortalMode, type Portal } from './portals.ts';
import type { PunctualLight } from './punctual-lights.ts';
import type { SunLight } from './sun-light.ts';
import type { Vec3 } from './vec3.ts';

/** How next-event estimation picks among bounded lights (emissive triangles, area, point and spot lights). */
export type WavefrontLightSamplerMode = 'auto' | 'tree' | 'power';

/** Bounded lights above which `lightSampler: 'auto'` uses the light tree rather than the power table. */
export const AUTO_LIGHT_TREE_THRESHOLD = 8;

/** A light of the `lights` option: KHR_lights_punctual or an area light. */
export type WavefrontSceneLightInput = WavefrontPunctualLightInput | WavefrontAreaLightInput;

/** The renderer's lighting options (beside the scene's `environment` and `lights`). */
export interface WavefrontLightingOptions {
  /**
   * An equirectangular HDR environment: RGBA texels (Float32Array, or Uint16Array of half floats),
   * row-major, row 0 the +Y zenith, u = fract(atan2(d.z, d.x) / 2 pi + 0.5 + rotationRadians / 2 pi),
   * v = acos(d.y) / pi (three.js's convention); radiance = texel x intensity. `loadEnvironmentMap`
   * reads .hdr and .exr files into this shape.
   */
  environmentMap?: EnvironmentMapInput;
  /** A physically based sky: Hosek-Wilkie clear sky with the sun disc, or the overcast and studio presets. */
  environmentLighting?: EnvironmentLightingInput;
  /** Rectangles (windows) through which the environment lights an interior; they steer sampling only. */
  environmentPortals?: EnvironmentPortalInput[];
  /** 'guide' (default) or 'guide-and-gate'; see the README. */
  environmentPortalMode?: EnvironmentPortalMode;
  /** 'auto' (default: the light tree above 8 bounded lights), 'tree' or 'power' (alias table by power). */
  lightSampler?: WavefrontLightSamplerMode;
  /**
   * How next-event estimation samples an environment map: 'importance' (default: in proportion to
   * luminance x sin(theta)) or 'uniform' (uniform directions; unbiased too, for measuring the gain).
   */
  environmentSampling?: 'importance' | 'uniform';
}

/** The validated environment the path tracer lights with. */
export type LightingEnvironment =
  | { kind: 'none' }
  | { kind: 'uniform'; radiance: Vec3 }
  | { kind: 'map'; map: EnvironmentMap; sun: SunLight | null; preset: EnvironmentLightingPreset | null };

export interface LightingConfig {
  environment: LightingEnvironment;
  punctual: PunctualLight[];
  area: AreaLight[];
  portals: Portal[];
  portalMode: EnvironmentPortalMode;
  lightSampler: WavefrontLightSamplerMode;
  environmentSampling: 'importance' | 'uniform';
}

const SAMPLER_MODES: readonly WavefrontLightSamplerMode[] = ['auto', 'tree', 'power'];

function checkMagnitude(values: readonly number[], limit: number, field: string, code: 'INVALID_LIGHT' | 'INVALID_ENVIRONMENT'): void {
  values.forEach((v, i) => {
    if (Math.abs(v) > limit) fail(code, `${field}[${i}]`, `magnitude ${v} exceeds the supported ${limit}`);
  });
}

/**
 * Checks the lighting options and the scene's `lights`: typed errors name the field
 * (`INVALID_ENVIRONMENT` for environments and portals, `INVALID_LIGHT` for lights, `INVALID_OPTION`
 * for conflicting options). Finite values whose float32 products would overflow on the GPU (radiance
 * beyond 1e20, coordinates beyond 1e18) are refused too.
 */
export function validateLightingOptions(
  options: WavefrontLightingOptions & { lights?: unknown },
  uniformEnvironment: Vec3,
): LightingConfig {
  const { environmentMap, environmentLighting } = options;
  if (environmentMap !== undefined && environmentLighting !== undefined) {
    fail('INVALID_OPTION', 'environmentLighting', 'give either environmentMap or environmentLighting, not both');
  }
  const hasUniform = uniformEnvironment.some((c) => c > 0);
  let environment: LightingEnvironment = hasUniform ? { kind: 'uniform', radiance: uniformEnvironment } : { kind: 'none' };
  if (environmentMap !== undefined || environmentLighting !== undefined) {
    if (hasUniform) fail('INVALID_OPTION', 'environment', `a uniform environment colour and ${environmentMap !== undefined ? 'environmentMap' : 'environmentLighting'} exclude each other`);
    if (environmentMap !== undefined) {
      const map = validateEnvironmentMap(environmentMap, 'environmentMap');
      let brightest = 0;
      for (let t = 0; t < map.width * map.height; t++) brightest = Math.max(brightest, map.data[4 * t]!, map.data[4 * t + 1]!, map.data[4 * t + 2]!);
      if (brightest * map.intensity > maxRadiance) fail('INVALID_ENVIRONMENT', 'environmentMap.intensity', `texel radiance x intensity ${brightest * map.intensity} exceeds the supported ${maxRadiance}`);
      environment = { kind: 'map', map, sun: null, preset: null };
    } else {
      const sky = createEnvironmentLighting(environmentLighting, 'environmentLighting');
      if (sky.sun) checkMagnitude(sky.sun.radiance, maxRadiance, 'environmentLighting.sunIntensity', 'INVALID_ENVIRONMENT');
      environment = { kind: 'map', map: sky.map, sun: sky.sun, preset: sky.preset };
    }
  }
  const lights = validateLights(options.lights, 'lights');
  lights.order.forEach((entry, i) => {
    const field = `lights[${i}]`;
    if (entry.kind === 'punctual') {
      const l = lights.punctual[entry.index]!;
      checkMagnitude(l.intensity, maxRadiance, `${field}.intensity`, 'INVALID_LIGHT');
      checkMagnitude(l.position, maxCoordinateMagnitude, `${field}.position`, 'INVALID_LIGHT');
    } else {
      const l = lights.area[entry.index]!;
      checkMagnitude(l.radiance, maxRadiance, `${field}.emission`, 'INVALID_LIGHT');
      checkMagnitude(l.center, maxCoordinateMagnitude, `${field}.center`, 'INVALID_LIGHT');
      checkMagnitude([...l.edgeU, ...l.edgeV, l.radius], maxCoordinateMagnitude, `${field}.${l.type === 'rectangle' ? 'edgeU' : 'radius'}`, 'INVALID_LIGHT');
    }
  });
  let portals: Portal[] = [];
  if (options.environmentPortals !== undefined) {
    portals = validateEnvironmentPortals(options.environmentPortals, 'environmentPortals');
    portals.forEach((p, i) => checkMagnitude([...p.corner, ...p.edgeU, ...p.edgeV], maxCoordinateMagnitude, `environmentPortals[${i}].center`, 'INVALID_ENVIRONMENT'));
    if (portals.length > 0 && environment.kind === 'none') fail('INVALID_ENVIRONMENT', 'environmentPortals', 'portals steer environment sampling: give an environment (environment, environmentMap or environmentLighting)');
  }
  const portalMode = validateEnvironmentPortalMode(options.environmentPortalMode, 'environmentPortalMode');
  const lightSampler = options.lightSampler ?? 'auto';
  if (!SAMPLER_MODES.includes(lightSampler)) fail('INVALID_OPTION', 'lightSampler', `expected one of ${SAMPLER_MODES.join(', ')}, got ${describe(lightSampler)}`);
  const environmentSampling = options.environmentSampling ?? 'importance';
  if (environmentSampling !== 'importance' && environmentSampling !== 'uniform') fail('INVALID_OPTION', 'environmentSampling', `expected 'importance' or 'uniform', got ${describe(environmentSampling)}`);
  return { environment, punctual: lights.punctual, area: lights.area, portals, portalMode, lightSampler, environmentSampling };
}

/** `--env-rotation` and scene files give degrees; the option takes radians. */
export function degreesToRadians(degrees: number): number {
  return (degrees * Math.PI) / 180;
}
