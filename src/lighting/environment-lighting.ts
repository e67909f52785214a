import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { describe, fail, requireFiniteNumber, requireInteger, requireVec } from '../errors/validate.ts';
import type { Vec3Input } from '../scene/types.ts';
import type { EnvironmentMap } from './environment-map.ts';
import { equirectUvToDirection } from './equirect.ts';
import { createHosekWilkieSky, hosekWilkieRadiance, type HosekWilkieSky } from './hosek-wilkie.ts';
import { CIE_OVERCAST_ILLUMINANCE_FACTOR, cieOvercastRadiance, studioRadiance } from './procedural-skies.ts';
import { LUMENS_PER_WATT, solarDiscRadiance } from './solar-radiance.ts';
import { oneMinusCos, sunSolidAngle, type SunLight } from './sun-light.ts';
import { add, dot, luminance, mul, normalize, scale, type Vec3 } from './vec3.ts';
import { requireKnownKeys } from './known-keys.ts';

/**
 * The `environmentLighting` option: procedural environments baked to an equirect map (sampled like
 * any environment map) plus, for clear skies, the sun as a separate disc light (sun-light.ts).
 *
 * Presets:
 * - 'clear' (default): Hosek-Wilkie clear sky (hosek-wilkie.ts) for `sunDirection`, `turbidity`,
 *   `groundAlbedo`, plus the sun disc (solar-radiance.ts) through the same turbidity;
 * - 'noon': 'clear' with the sun 60 degrees high, turbidity 3;
 * - 'sunset': 'clear' with the sun 4 degrees high, turbidity 4;
 * - 'overcast': CIE standard overcast sky, no sun disc, horizontal illuminance 10 klux by default;
 * - 'studio': a neutral studio dome of softboxes (procedural-skies.ts).
 * Below the horizon every preset but 'studio' shows a Lambertian ground of `groundAlbedo` lit by
 * the sky and sun: radiance albedo x E_h / pi.
 *
 * Units: cd/m^2 (nits) per channel, the unit of KHR_materials_emissive_strength and of
 * KHR_lights_punctual's candela and lux, so these lights and a glTF scene's lights agree. Daylight
 * is bright (a white surface under the noon sun is ~3e4 nits): pair it with the `exposure` of the
 * result's `suggestedExposure`.
 */
export type EnvironmentLightingPreset = 'clear' | 'noon' | 'sunset' | 'overcast' | 'studio';

export interface EnvironmentLightingInput {
  preset?: EnvironmentLightingPreset;
  /** Towards the sun, +Y up (any length). Clear-sky presets; the sun must be above the horizon. */
  sunDirection?: Vec3Input;
  /** Atmospheric turbidity, 1 (pure air) .. 10 (haze): Hosek-Wilkie's fitted range. */
  turbidity?: number;
  /** Ground albedo in [0, 1], grey or RGB; default 0.3. */
  groundAlbedo?: number | Vec3Input;
  /** Multiplies the sun's radiance per channel; default [1, 1, 1]. */
  sunColor?: Vec3Input;
  /** Multiplies the sun's radiance; default 1; 0 removes the sun disc. */
  sunIntensity?: number;
  /** Multiplies the sky dome (and the ground it lights); default 1. */
  skyIntensity?: number;
  /** Angular diameter of the sun disc in degrees, (0, 5]; default 0.53. */
  sunAngularDiameterDegrees?: number;
  /** Eddington limb darkening of the disc; default true. */
  sunLimbDarkening?: boolean;
  /** 'overcast': zenith luminance in cd/m^2; default 10,000 lux / (7 pi / 9) = 4093. */
  zenithLuminance?: number;
  /** Size of the baked map; default 512 x 256. */
  width?: number;
  height?: number;
}

export interface EnvironmentLighting {
  preset: EnvironmentLightingPreset;
  /** Sky (and ground) radiance, without the sun disc. */
  map: EnvironmentMap;
  /** The sun disc, or null (overcast, studio, sunIntensity 0). */
  sun: SunLight | null;
  /** Illuminance on an upward-facing surface from sky and sun, lux. */
  horizontalIlluminance: number;
  /**
   * pi / (the largest illuminance on the six axis-aligned faces of a cube): the exposure at which a
   * white Lambertian surface facing the brightest direction has radiance about 1.
   */
  suggestedExposure: number;
}

const CODE = 'INVALID_ENVIRONMENT';
const PRESETS: readonly EnvironmentLightingPreset[] = ['clear', 'noon', 'sunset', 'overcast', 'studio'];

function directionFromElevationAzimuth(elevationDeg: number, azimuthDeg: number): Vec3 {
  const e = (elevationDeg * Math.PI) / 180;
  const a = (azimuthDeg * Math.PI) / 180;
  return [Math.cos(e) * Math.cos(a), Math.sin(e), Math.cos(e) * Math.sin(a)];
}

const PRESET_DEFAULTS: Record<'clear' | 'noon' | 'sunset', { sun: Vec3; turbidity: number }> = {
  clear: { sun: directionFromElevationAzimuth(60, 135), turbidity: 3 },
  noon: { sun: directionFromElevationAzimuth(60, 135), turbidity: 3 },
  sunset: { sun: directionFromElevationAzimuth(4, 200), turbidity: 4 },
};

interface ValidatedLighting {
  preset: EnvironmentLightingPreset;
  sunDirection: Vec3;
  turbidity: number;
  groundAlbedo: Vec3;
  sunColor: Vec3;
  sunIntensity: number;
  skyIntensity: number;
  sunAngularRadius: number;
  sunLimbDarkening: boolean;
  zenithLuminance: number;
  width: number;
  height: number;
}

function nonNegative(value: unknown, field: string, fallback: number): number {
  if (value === undefined) return fallback;
  const n = requireFiniteNumber(value, field, CODE);
  if (n < 0) fail(CODE, field, `must be >= 0, got ${n}`);
  return n;
}

/** Checks an `environmentLighting` option; `INVALID_ENVIRONMENT` errors name the field. */
export function validateEnvironmentLighting(input: unknown, field = 'environmentLighting'): ValidatedLighting {
  if (typeof input !== 'object' || input === null || Array.isArray(input)) fail(CODE, field, `expected an object, got ${describe(input)}`);
  const v = input as Record<string, unknown>;
  requireKnownKeys(v, ['preset', 'sunDirection', 'turbidity', 'groundAlbedo', 'sunColor', 'sunIntensity', 'skyIntensity', 'sunAngularDiameterDegrees', 'sunLimbDarkening', 'zenithLuminance', 'width', 'height'], field, CODE);
  const preset = (v.preset ?? 'clear') as EnvironmentLightingPreset;
  if (!PRESETS.includes(preset)) fail(CODE, `${field}.preset`, `expected one of ${PRESETS.join(', ')}, got ${describe(v.preset)}`);
  const defaults = preset === 'noon' || preset === 'sunset' || preset === 'clear' ? PRESET_DEFAULTS[preset] : PRESET_DEFAULTS.clear;
  let sunDirection = defaults.sun;
  if (v.sunDirection !== undefined) {
    const d = requireVec(v.sunDirection, 3, `${field}.sunDirection`, CODE);
    if (!(Math.hypot(d[0]!, d[1]!, d[2]!) > 0)) fail(CODE, `${field}.sunDirection`, 'must be a non-zero vector');
    sunDirection = normalize(d);
  }
  const clearSky = preset === 'clear' || preset === 'noon' || preset === 'sunset';
  if (clearSky && sunDirection[1] < 0) fail(CODE, `${field}.sunDirection`, 'the sun must be above the horizon (y >= 0): the clear-sky model covers solar elevations 0 to 90 degrees');
  const turbidity = v.turbidity === undefined ? defaults.turbidity : requireFiniteNumber(v.turbidity, `${field}.turbidity`, CODE);
  if (!(turbidity >= 1 && turbidity <= 10)) fail(CODE, `${field}.turbidity`, `must be in [1, 10], got ${turbidity}`);
  let groundAlbedo: Vec3;
  if (typeof v.groundAlbedo === 'number' || v.groundAlbedo === undefined) {
    const a = v.groundAlbedo === undefined ? 0.3 : requireFiniteNumber(v.groundAlbedo, `${field}.groundAlbedo`, CODE);
    if (!(a >= 0 && a <= 1)) fail(CODE, `${field}.groundAlbedo`, `must be in [0, 1], got ${a}`);
    groundAlbedo = [a, a, a];
  } else {
    const a = requireVec(v.groundAlbedo, 3, `${field}.groundAlbedo`, CODE);
    a.forEach((x, i) => {
      if (!(x >= 0 && x <= 1)) fail(CODE, `${field}.groundAlbedo[${i}]`, `must be in [0, 1], got ${x}`);
    });
    groundAlbedo = a as Vec3;
  }
  let sunColor: Vec3 = [1, 1, 1];
  if (v.sunColor !== undefined) {
    const c = requireVec(v.sunColor, 3, `${field}.sunColor`, CODE);
    c.forEach((x, i) => {
      if (x < 0) fail(CODE, `${field}.sunColor[${i}]`, `must be >= 0, got ${x}`);
    });
    sunColor = c as Vec3;
  }
  const sunIntensity = nonNegative(v.sunIntensity, `${field}.sunIntensity`, 1);
  const skyIntensity = nonNegative(v.skyIntensity, `${field}.skyIntensity`, 1);
  const diameter = v.sunAngularDiameterDegrees === undefined ? 0.53 : requireFiniteNumber(v.sunAngularDiameterDegrees, `${field}.sunAngularDiameterDegrees`, CODE);
  if (!(diameter > 0 && diameter <= 5)) fail(CODE, `${field}.sunAngularDiameterDegrees`, `must be in (0, 5], got ${diameter}`);
  if (v.sunLimbDarkening !== undefined && typeof v.sunLimbDarkening !== 'boolean') fail(CODE, `${field}.sunLimbDarkening`, `expected a boolean, got ${describe(v.sunLimbDarkening)}`);
  const zenithLuminance = nonNegative(v.zenithLuminance, `${field}.zenithLuminance`, 10000 / CIE_OVERCAST_ILLUMINANCE_FACTOR);
  const width = v.width === undefined ? 512 : requireInteger(v.width, `${field}.width`, { min: 4, max: 8192 }, CODE);
  const height = v.height === undefined ? 256 : requireInteger(v.height, `${field}.height`, { min: 2, max: 8192 }, CODE);
  return {
    preset,
    sunDirection,
    turbidity,
    groundAlbedo,
    sunColor,
    sunIntensity,
    skyIntensity,
    sunAngularRadius: (diameter / 2) * (Math.PI / 180),
    sunLimbDarkening: v.sunLimbDarkening !== false,
    zenithLuminance,
    width,
    height,
  };
}

/** Upper-hemisphere sky radiance (nits, before skyIntensity) of a validated clear sky. */
export function clearSkyRadiance(sky: HosekWilkieSky, sunDirection: Vec3, d: readonly number[]): Vec3 {
  const theta = Math.acos(Math.min(1, Math.max(0, d[1]!)));
  const gamma = Math.acos(Math.min(1, Math.max(-1, dot(d, sunDirection))));
  return scale(hosekWilkieRadiance(sky, theta, gamma), LUMENS_PER_WATT);
}

/** Upper-hemisphere radiance function of the preset (nits, x skyIntensity), and the sun disc. */
function describeSky(l: ValidatedLighting): { upper: (d: readonly number[]) => Vec3; sun: SunLight | null; ground: boolean } {
  if (l.preset === 'studio') return { upper: (d) => scale(studioRadiance(d), l.skyIntensity), sun: null, ground: false };
  if (l.preset === 'overcast') return { upper: (d) => scale(cieOvercastRadiance(l.zenithLuminance, d), l.skyIntensity), sun: null, ground: true };
  const elevation = Math.asin(Math.min(1, l.sunDirection[1]));
  const sky = createHosekWilkieSky(l.turbidity, l.groundAlbedo, elevation);
  const radiance = scale(mul(solarDiscRadiance(elevation, l.turbidity), l.sunColor), l.sunIntensity);
  const sun: SunLight | null =
    luminance(radiance) > 0
      ? { direction: l.sunDirection, oneMinusCosThetaMax: oneMinusCos(l.sunAngularRadius), radiance, limbDarkening: l.sunLimbDarkening }
      : null;
  return { upper: (d) => scale(clearSkyRadiance(sky, l.sunDirection, d), l.skyIntensity), sun, ground: true };
}

/**
 * Builds the environment: bakes the sky to an equirect map (each texel the mean of 2 x 2 radiance
 * samples; below the horizon the ground), and returns the sun disc separately.
 */
export function createEnvironmentLighting(input: unknown, field = 'environmentLighting'): EnvironmentLighting {
  const l = validateEnvironmentLighting(input, field);
  const { upper, sun, ground } = describeSky(l);
  const { width: w, height: h } = l;
  const data = new Float32Array(w * h * 4);
  const below = new Uint8Array(w * h * 4);
  const ss = 2;
  for (let j = 0; j < h; j++) {
    for (let i = 0; i < w; i++) {
      const acc = [0, 0, 0];
      let under = 0;
      for (let a = 0; a < ss; a++) {
        for (let b = 0; b < ss; b++) {
          const d = equirectUvToDirection((i + (a + 0.5) / ss) / w, (j + (b + 0.5) / ss) / h);
          if (d[1] < 0 && ground) {
            under++;
            continue;
          }
          const r = upper(d);
          for (let c = 0; c < 3; c++) acc[c] = acc[c]! + r[c]!;
        }
      }
      const o = 4 * (j * w + i);
      for (let c = 0; c < 3; c++) data[o + c] = acc[c]! / (ss * ss);
      data[o + 3] = 1;
      below[o] = under;
    }
  }
  // Horizontal irradiance from sky and sun, per channel: the ground is a Lambertian reflector of it.
  const skyIrradiance = irradianceFromMap(data, w, h, [0, 1, 0], (d) => d[1]! > 0);
  const sunIrradiance = sun ? scale(sun.radiance, sunSolidAngle(sun) * Math.max(0, sun.direction[1])) : ([0, 0, 0] as Vec3);
  const horizontal = add(skyIrradiance, sunIrradiance);
  const horizontalIlluminance = luminance(horizontal);
  if (ground) {
    const groundRadiance = scale(mul(l.groundAlbedo, horizontal), 1 / Math.PI);
    for (let t = 0; t < w * h; t++) {
      const n = below[4 * t]!;
      if (n === 0) continue;
      for (let c = 0; c < 3; c++) data[4 * t + c] = data[4 * t + c]! + (groundRadiance[c]! * n) / (ss * ss);
    }
  }
  let brightest = 0;
  for (const axis of [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]] as Vec3[]) {
    const e = luminance(irradianceFromMap(data, w, h, axis, () => true)) + (sun ? luminance(sun.radiance) * sunSolidAngle(sun) * Math.max(0, dot(axis, sun.direction)) : 0);
    brightest = Math.max(brightest, e);
  }
  const map: EnvironmentMap = { width: w, height: h, data, intensity: 1, rotationRadians: 0 };
  for (let k = 0; k < data.length; k++) {
    if (!Number.isFinite(data[k]!) || data[k]! < 0) throw new GpuRendererError(CODE, `sky model produced ${data[k]} at texel ${k >> 2}`, { field });
  }
  return { preset: l.preset, map, sun, horizontalIlluminance, suggestedExposure: brightest > 0 ? Math.PI / brightest : 1 };
}

/** Irradiance (RGB) on a surface with normal `n` from the baked texels (midpoint rule). */
function irradianceFromMap(data: Float32Array, w: number, h: number, n: Vec3, include: (d: readonly number[]) => boolean): Vec3 {
  const e: Vec3 = [0, 0, 0];
  for (let j = 0; j < h; j++) {
    const v = (j + 0.5) / h;
    const sinTheta = Math.sin(Math.PI * v);
    for (let i = 0; i < w; i++) {
      const d = equirectUvToDirection((i + 0.5) / w, v);
      const c = dot(d, n);
      if (c <= 0 || !include(d)) continue;
      const o = 4 * (j * w + i);
      for (let k = 0; k < 3; k++) e[k] += data[o + k]! * c * sinTheta;
    }
  }
  return scale(e, (2 * Math.PI * Math.PI) / (w * h));
}
