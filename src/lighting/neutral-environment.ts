import { fail, requireFiniteNumber, requireInteger, describe } from '../errors/validate.ts';
import type { EnvironmentMap } from './environment-map.ts';
import { requireKnownKeys } from './known-keys.ts';
import type { StudioSoftbox } from './procedural-skies.ts';

/**
 * The built-in neutral studio environment: what a scene with no light is lit by where a default is
 * asked for (the CLI, `loadGltfScene`'s `defaultLighting: 'neutral'`), as model-viewer, the glTF
 * Sample Viewer and Blender light a bare model. Procedural (no file), neutral grey (equal RGB, so
 * materials keep their colours), in the renderer's linear radiance units: a white Lambertian
 * surface facing the camera has radiance about 1, so exposure 1 shows it.
 *
 * Radiance is a function of direction (+Y up, azimuth atan2(z, x) as in equirect.ts):
 * - a grey dome, DOME_HORIZON + DOME_GRADIENT * y above the horizon and FLOOR below;
 * - plus three rectangular softboxes in (azimuth, elevation) (elevations within [0, 90]), added to the dome: a broad key
 *   front-left, a weaker fill front-right and a rim behind (the front is +Z, where the glTF
 *   loader's framing camera stands).
 * Each texel of the baked map is the exact solid-angle mean of that function over the texel, so
 * the map integrates to `neutralEnvironmentMeanRadiance()` exactly (up to float rounding), and it is
 * importance-sampled like any other environment map.
 */

/** Dome radiance at the horizon and its rise to the zenith (linear, per channel). */
export const NEUTRAL_DOME_HORIZON = 0.4;
export const NEUTRAL_DOME_GRADIENT = 0.3;
/** Radiance below the horizon: a darker grey floor. */
export const NEUTRAL_FLOOR = 0.25;

/**
 * The softboxes, in the studio preset's angular form (procedural-skies.ts); `luminance` is the
 * radiance added to the dome (the renderer's radiance unit is the nit).
 */
export const NEUTRAL_SOFTBOXES: readonly StudioSoftbox[] = [
  { azimuthDegrees: 135, elevationDegrees: 35, widthDegrees: 50, heightDegrees: 35, luminance: 4 },
  { azimuthDegrees: 45, elevationDegrees: 20, widthDegrees: 60, heightDegrees: 35, luminance: 1.5 },
  { azimuthDegrees: 270, elevationDegrees: 45, widthDegrees: 30, heightDegrees: 40, luminance: 2.5 },
];

const RAD = Math.PI / 180;

/** The environment's radiance (one channel: it is grey) towards unit direction `d`. */
export function neutralEnvironmentRadiance(d: readonly number[]): number {
  const y = Math.max(-1, Math.min(1, d[1]!));
  if (y < 0) return NEUTRAL_FLOOR;
  let l = NEUTRAL_DOME_HORIZON + NEUTRAL_DOME_GRADIENT * y;
  const elevation = Math.asin(y) / RAD;
  const azimuth = Math.atan2(d[2]!, d[0]!) / RAD;
  for (const box of NEUTRAL_SOFTBOXES) {
    let da = Math.abs(azimuth - box.azimuthDegrees) % 360;
    if (da > 180) da = 360 - da;
    if (da < box.widthDegrees / 2 && Math.abs(elevation - box.elevationDegrees) < box.heightDegrees / 2) l += box.luminance;
  }
  return l;
}

/** Length of the overlap of [a0, a1] with [b0, b1]. */
function overlap(a0: number, a1: number, b0: number, b1: number): number {
  return Math.max(0, Math.min(a1, b1) - Math.max(a0, b0));
}

/** Overlap in radians of the azimuth interval [p0, p1] (radians, within [-pi, pi]) with a softbox's, wrapping. */
function azimuthOverlap(p0: number, p1: number, box: StudioSoftbox): number {
  const from = (box.azimuthDegrees - box.widthDegrees / 2) * RAD;
  const to = (box.azimuthDegrees + box.widthDegrees / 2) * RAD;
  let total = 0;
  for (const shift of [-2 * Math.PI, 0, 2 * Math.PI]) total += overlap(p0, p1, from + shift, to + shift);
  return total;
}

/**
 * Integral of the radiance over the cell azimuth [p0, p1] x polar angle [t0, t1] (radians), in
 * closed form: dω = sinθ dθ dφ, the dome's y = cosθ, a softbox's elevation e has sin e = cosθ.
 */
function cellIntegral(p0: number, p1: number, t0: number, t1: number): number {
  const c0 = Math.cos(t0);
  const c1 = Math.cos(t1);
  const dPhi = p1 - p0;
  // Upper part: cos theta from max(c1, 0) to c0, where c0 > 0.
  const upTop = Math.max(0, c0);
  const upBottom = Math.max(0, c1);
  let sum = dPhi * (NEUTRAL_DOME_HORIZON * (upTop - upBottom) + (NEUTRAL_DOME_GRADIENT * (upTop * upTop - upBottom * upBottom)) / 2);
  sum += dPhi * NEUTRAL_FLOOR * (Math.min(0, c0) - Math.min(0, c1));
  for (const box of NEUTRAL_SOFTBOXES) {
    const cosOverlap = overlap(c1, c0, Math.sin((box.elevationDegrees - box.heightDegrees / 2) * RAD), Math.sin((box.elevationDegrees + box.heightDegrees / 2) * RAD));
    sum += box.luminance * azimuthOverlap(p0, p1, box) * cosOverlap;
  }
  return sum;
}

/** The environment's mean radiance over the sphere, (1 / 4π) ∫ L dω, in closed form. */
export function neutralEnvironmentMeanRadiance(): number {
  return cellIntegral(-Math.PI, Math.PI, 0, Math.PI) / (4 * Math.PI);
}

export interface NeutralEnvironmentOptions {
  /** Size of the baked map; default 512 x 256 (height even, so the horizon is a texel edge). */
  width?: number;
  height?: number;
  /** Radiance multiplier, default 1. */
  intensity?: number;
  /** Rotation about +Y in radians, default 0. */
  rotationRadians?: number;
}

/**
 * Bakes the neutral studio environment to an equirect map (an `environmentMap` option): each
 * texel the exact mean radiance over its solid angle. `INVALID_ENVIRONMENT` errors name the option.
 */
export function createNeutralEnvironment(options: NeutralEnvironmentOptions = {}, field = 'neutralEnvironment'): EnvironmentMap {
  const code = 'INVALID_ENVIRONMENT';
  if (typeof options !== 'object' || options === null || Array.isArray(options)) fail(code, field, `expected an object, got ${describe(options)}`);
  requireKnownKeys(options as Record<string, unknown>, ['width', 'height', 'intensity', 'rotationRadians'], field, code);
  const width = options.width === undefined ? 512 : requireInteger(options.width, `${field}.width`, { min: 4, max: 8192 }, code);
  const height = options.height === undefined ? 256 : requireInteger(options.height, `${field}.height`, { min: 2, max: 8192 }, code);
  if (height % 2 !== 0) fail(code, `${field}.height`, `must be even (the horizon is a texel edge), got ${height}`);
  const intensity = options.intensity === undefined ? 1 : requireFiniteNumber(options.intensity, `${field}.intensity`, code);
  if (intensity < 0) fail(code, `${field}.intensity`, `must be >= 0, got ${intensity}`);
  const rotationRadians = options.rotationRadians === undefined ? 0 : requireFiniteNumber(options.rotationRadians, `${field}.rotationRadians`, code);
  const data = new Float32Array(width * height * 4);
  for (let j = 0; j < height; j++) {
    const t0 = (Math.PI * j) / height;
    const t1 = (Math.PI * (j + 1)) / height;
    const solidAngleOverDPhi = Math.cos(t0) - Math.cos(t1);
    for (let i = 0; i < width; i++) {
      // equirect.ts: phi = 2 pi u - pi.
      const p0 = (2 * Math.PI * i) / width - Math.PI;
      const p1 = (2 * Math.PI * (i + 1)) / width - Math.PI;
      const l = cellIntegral(p0, p1, t0, t1) / ((p1 - p0) * solidAngleOverDPhi);
      const o = 4 * (j * width + i);
      data[o] = data[o + 1] = data[o + 2] = l;
      data[o + 3] = 1;
    }
  }
  return { width, height, data, intensity, rotationRadians };
}
