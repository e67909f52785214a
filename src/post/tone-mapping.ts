/**
 * CPU mirror of src/shaders/wgsl/tonemap.wgsl: the display transform from scene-referred linear
 * radiance to display-referred sRGB. Tests compare this file against the WGSL on the GPU, so the
 * two must stay formula-for-formula identical.
 */
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import type { WavefrontToneMapping } from '../scene/types.ts';

export type Rgb = [number, number, number];
type RgbInput = readonly [number, number, number] | readonly number[];

/** The `mode` value the WGSL `apply_tone_mapping` takes for each tone mapping. */
export const toneMappingModeIds: Readonly<Record<WavefrontToneMapping, number>> = { neutral: 0, aces: 1, linear: 2 };

export const toneMappingNames: readonly WavefrontToneMapping[] = ['neutral', 'aces', 'linear'];

export function isToneMapping(value: unknown): value is WavefrontToneMapping {
  return typeof value === 'string' && (toneMappingNames as readonly string[]).includes(value);
}

/**
 * Khronos PBR Neutral, after the reference code at
 * https://github.com/KhronosGroup/ToneMapping/blob/main/PBR_Neutral/pbrNeutral.glsl
 */
export function toneMapPbrNeutral(rgb: RgbInput): Rgb {
  const startCompression = 0.8 - 0.04;
  const desaturation = 0.15;
  let r = rgb[0];
  let g = rgb[1];
  let b = rgb[2];
  const x = Math.min(r, g, b);
  const offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
  r -= offset;
  g -= offset;
  b -= offset;
  const peak = Math.max(r, g, b);
  if (peak < startCompression) return [r, g, b];
  const d = 1 - startCompression;
  const newPeak = 1 - (d * d) / (peak + d - startCompression);
  const scale = newPeak / peak;
  r *= scale;
  g *= scale;
  b *= scale;
  const t = 1 - 1 / (desaturation * (peak - newPeak) + 1);
  return [r + (newPeak - r) * t, g + (newPeak - g) * t, b + (newPeak - b) * t];
}

/** The rational fit of the ACES RRT + sRGB ODT by Stephen Hill (BakingLab ACES.hlsl). */
function rrtAndOdtFit(v: number): number {
  const a = v * (v + 0.0245786) - 0.000090537;
  const b = v * (0.983729 * v + 0.432951) + 0.238081;
  return a / b;
}

const clamp01 = (v: number): number => Math.min(Math.max(v, 0), 1);

/**
 * Stephen Hill's fitted ACES (https://github.com/TheRealMJP/BakingLab/blob/master/BakingLab/ACES.hlsl)
 * in linear sRGB with its input (sRGB -> AP1 + RRT saturation) and output (ODT saturation -> sRGB)
 * matrices: the curve three.js's ACESFilmicToneMapping uses, without three.js's extra 1/0.6
 * exposure boost. Output is clamped to [0, 1] as in the reference.
 */
export function toneMapAces(rgb: RgbInput): Rgb {
  const [r, g, b] = [rgb[0], rgb[1], rgb[2]];
  // Row-major here; the WGSL writes the same matrices as columns.
  const ir = rrtAndOdtFit(0.59719 * r + 0.35458 * g + 0.04823 * b);
  const ig = rrtAndOdtFit(0.076 * r + 0.90834 * g + 0.01566 * b);
  const ib = rrtAndOdtFit(0.0284 * r + 0.13383 * g + 0.83777 * b);
  return [
    clamp01(1.60475 * ir - 0.53108 * ig - 0.07367 * ib),
    clamp01(-0.10208 * ir + 1.10813 * ig - 0.00605 * ib),
    clamp01(-0.00327 * ir - 0.07276 * ig + 1.07602 * ib),
  ];
}

/** Exact sRGB encoding (IEC 61966-2-1:1999), scalar. */
export function linearToSrgb(x: number): number {
  return x <= 0.0031308 ? x * 12.92 : 1.055 * Math.pow(x, 1 / 2.4) - 0.055;
}

/** Exact sRGB decoding (IEC 61966-2-1:1999), scalar; the inverse of linearToSrgb. */
export function srgbToLinear(x: number): number {
  return x <= 0.04045 ? x / 12.92 : Math.pow((x + 0.055) / 1.055, 2.4);
}

/** Display-referred linear RGB in [0, 1]; exposure is applied by the caller before this. */
export function applyToneMapping(rgb: RgbInput, mode: WavefrontToneMapping): Rgb {
  const x: Rgb = [Math.max(rgb[0], 0), Math.max(rgb[1], 0), Math.max(rgb[2], 0)];
  let mapped: Rgb;
  switch (mode) {
    case 'aces':
      mapped = toneMapAces(x);
      break;
    case 'linear':
      // Clamped only for display; the radiance itself is never clamped.
      mapped = x;
      break;
    case 'neutral':
      mapped = toneMapPbrNeutral(x);
      break;
    default:
      throw new GpuRendererError('INVALID_OPTION', `unknown tone mapping ${JSON.stringify(mode)} (expected neutral, aces or linear)`, {
        field: 'toneMapping',
      });
  }
  return [clamp01(mapped[0]), clamp01(mapped[1]), clamp01(mapped[2])];
}

export interface EncodeRadianceOptions {
  /** Default 'neutral'. */
  toneMapping?: WavefrontToneMapping;
  /** Multiplier applied to radiance before tone mapping; default 1. */
  exposure?: number;
}

/**
 * Linear RGBA radiance (alpha ignored) -> tone-mapped sRGB RGBA8 with opaque alpha. Quantisation
 * rounds to nearest as WGSL's pack4x8unorm does (floor(0.5 + 255 x)). Non-finite radiance values
 * (which the renderer never produces; it drops and counts invalid samples) encode as 0.
 */
export function encodeRadianceToRgba8(radiance: Float32Array, options: EncodeRadianceOptions = {}): Uint8ClampedArray {
  const mode = options.toneMapping ?? 'neutral';
  if (!isToneMapping(mode)) {
    throw new GpuRendererError('INVALID_OPTION', `unknown tone mapping ${JSON.stringify(mode)} (expected neutral, aces or linear)`, {
      field: 'toneMapping',
    });
  }
  const exposure = options.exposure ?? 1;
  if (typeof exposure !== 'number' || !Number.isFinite(exposure) || exposure < 0) {
    throw new GpuRendererError('INVALID_OPTION', `expected a finite number >= 0, got ${String(exposure)}`, { field: 'exposure' });
  }
  if (radiance.length % 4 !== 0) {
    throw new GpuRendererError('INVALID_OPTION', `expected RGBA data (length a multiple of 4), got length ${radiance.length}`, {
      field: 'radiance',
    });
  }
  const out = new Uint8ClampedArray(radiance.length);
  const px: Rgb = [0, 0, 0];
  for (let i = 0; i < radiance.length; i += 4) {
    for (let c = 0; c < 3; c++) {
      const v = radiance[i + c] * exposure;
      px[c] = Number.isFinite(v) ? v : 0;
    }
    const mapped = applyToneMapping(px, mode);
    for (let c = 0; c < 3; c++) out[i + c] = Math.floor(0.5 + 255 * linearToSrgb(mapped[c]));
    out[i + 3] = 255;
  }
  return out;
}
