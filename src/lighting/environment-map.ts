import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { describe, fail, requireFiniteNumber, requireInteger } from '../errors/validate.ts';
import { directionToEquirectUv } from './equirect.ts';
import { halfBitsToFloat32 } from '../math/half-float.ts';
import type { Vec3 } from './vec3.ts';
import { requireKnownKeys } from './known-keys.ts';
import { maxRadiance } from '../scene/limits.ts';

/**
 * The `environmentMap` option: an equirectangular radiance map (see equirect.ts for the mapping).
 * `data` is RGBA, row-major, row 0 = the +Y zenith, linear radiance, as float32 or as half floats
 * (Uint16Array of binary16 bits). Alpha is not radiance and is ignored.
 */
export interface EnvironmentMapInput {
  width: number;
  height: number;
  data: Float32Array | Uint16Array;
  /** Radiance multiplier, default 1. */
  intensity?: number;
  /** Rotation about +Y in radians, default 0 (adds rotation / (2 pi) to u). */
  rotationRadians?: number;
}

/** A validated environment map: float32 RGBA with alpha set to 1, radiance = texel x intensity. */
export interface EnvironmentMap {
  readonly width: number;
  readonly height: number;
  readonly data: Float32Array;
  readonly intensity: number;
  readonly rotationRadians: number;
}

/** WebGPU's default maxTextureDimension2D: the map must fit one 2D texture. */
export const MAX_ENVIRONMENT_MAP_DIMENSION = 8192;

const CHANNELS = ['R', 'G', 'B'] as const;

/**
 * Checks an `environmentMap` option and returns it as float32 RGBA. Typed errors
 * (`INVALID_ENVIRONMENT`) name the field: sizes, the data's type and length, and the first texel
 * whose radiance is negative or not finite (`environmentMap.data[4 * texel + channel]`).
 */
export function validateEnvironmentMap(input: unknown, field = 'environmentMap'): EnvironmentMap {
  const code = 'INVALID_ENVIRONMENT';
  if (typeof input !== 'object' || input === null || Array.isArray(input)) fail(code, field, `expected an object, got ${describe(input)}`);
  const value = input as Record<string, unknown>;
  requireKnownKeys(value, ['width', 'height', 'data', 'intensity', 'rotationRadians'], field, code);
  const width = requireInteger(value.width, `${field}.width`, { min: 1, max: MAX_ENVIRONMENT_MAP_DIMENSION }, code);
  const height = requireInteger(value.height, `${field}.height`, { min: 1, max: MAX_ENVIRONMENT_MAP_DIMENSION }, code);
  const raw = value.data;
  const isHalf = raw instanceof Uint16Array;
  if (!(raw instanceof Float32Array) && !isHalf) {
    fail(code, `${field}.data`, `expected a Float32Array or a Uint16Array of half floats, got ${describe(raw)}`);
  }
  const expected = width * height * 4;
  if (raw.length !== expected) {
    fail(code, `${field}.data`, `expected ${expected} values (${width} x ${height} RGBA texels), got ${raw.length}`);
  }
  const intensity = value.intensity === undefined ? 1 : requireFiniteNumber(value.intensity, `${field}.intensity`, code);
  if (intensity < 0) fail(code, `${field}.intensity`, `must be >= 0, got ${intensity}`);
  const rotationRadians = value.rotationRadians === undefined ? 0 : requireFiniteNumber(value.rotationRadians, `${field}.rotationRadians`, code);
  const data = new Float32Array(expected);
  let brightest = 0;
  for (let t = 0; t < width * height; t++) {
    for (let c = 0; c < 3; c++) {
      const v = isHalf ? halfBitsToFloat32(raw[4 * t + c]!) : raw[4 * t + c]!;
      if (!Number.isFinite(v) || v < 0) {
        throw new GpuRendererError(
          code,
          `texel ${t} (x ${t % width}, y ${Math.floor(t / width)}) channel ${CHANNELS[c]} is ${v}: radiance must be finite and >= 0`,
          { field: `${field}.data[${4 * t + c}]` },
        );
      }
      data[4 * t + c] = v;
      if (v > brightest) brightest = v;
    }
    data[4 * t + 3] = 1;
  }
  // Radiance the renderer supports (scene/limits.ts): beyond it float32 sums on the GPU overflow.
  if (brightest * intensity > maxRadiance) fail(code, `${field}.intensity`, `texel radiance x intensity ${brightest * intensity} exceeds the supported ${maxRadiance}`);
  return { width, height, data, intensity, rotationRadians };
}

/**
 * Bilinearly filtered texel value at (u, v) (texel centres at ((i + 0.5) / W, (j + 0.5) / H)),
 * wrapping in u and clamping in v: what a GPU sampler with addressModeU 'repeat', addressModeV
 * 'clamp-to-edge' and linear filtering returns. Without the intensity.
 */
export function bilinearTexel(map: Pick<EnvironmentMap, 'width' | 'height' | 'data'>, u: number, v: number): Vec3 {
  const { width: w, height: h, data } = map;
  const x = u * w - 0.5;
  const y = v * h - 0.5;
  const x0f = Math.floor(x);
  const y0f = Math.floor(y);
  const fx = x - x0f;
  const fy = y - y0f;
  const x0 = ((x0f % w) + w) % w;
  const x1 = (x0 + 1) % w;
  const y0 = Math.min(h - 1, Math.max(0, y0f));
  const y1 = Math.min(h - 1, Math.max(0, y0f + 1));
  const out: Vec3 = [0, 0, 0];
  for (let c = 0; c < 3; c++) {
    const a = data[4 * (y0 * w + x0) + c]! * (1 - fx) + data[4 * (y0 * w + x1) + c]! * fx;
    const b = data[4 * (y1 * w + x0) + c]! * (1 - fx) + data[4 * (y1 * w + x1) + c]! * fx;
    out[c] = a * (1 - fy) + b * fy;
  }
  return out;
}

/** Radiance arriving from unit direction `d` (bilinear lookup x intensity). */
export function environmentRadiance(map: EnvironmentMap, d: readonly number[]): Vec3 {
  const [u, v] = directionToEquirectUv(d, map.rotationRadians);
  const t = bilinearTexel(map, u, v);
  return [t[0] * map.intensity, t[1] * map.intensity, t[2] * map.intensity];
}
