/**
 * CPU mirror of src/film/display/tonemap.wesl: the display transform from scene-referred linear
 * radiance to display-referred sRGB. Tests compare this file against the WGSL on the GPU, so the
 * two must stay formula-for-formula identical.
 */
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import type { WavefrontToneMapping } from '../scene/types.ts';
import { linearToSrgb } from '../color/srgb.ts';

export { linearToSrgb, srgbToLinear } from '../color/srgb.ts';

export type Rgb = [number, number, number];
type RgbInput = readonly [number, number, number] | readonly number[];

/** Every display transform (the renderer's `toneMapping` values). */
export type ToneMappingMode = WavefrontToneMapping;

/** The `mode` value the WGSL `apply_tone_mapping` takes for each tone mapping (TONE_MAPPING_* ids). */
export const toneMappingModeIds: Readonly<Record<ToneMappingMode, number>> = { neutral: 0, aces: 1, linear: 2, agx: 3 };

export const toneMappingNames: readonly ToneMappingMode[] = ['neutral', 'aces', 'linear', 'agx'];

export function isToneMapping(value: unknown): value is ToneMappingMode {
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

// Linear Rec. 709 (sRGB primaries) <-> linear Rec. 2020, both with a D65 white: derived in double
// precision from the ITU-R BT.709 and BT.2020 primaries (three.js uses the same matrices rounded
// to 4 decimals, after ITU-R BT.2407). Row-major.
const rec709ToRec2020 = [
  [0.627403895934699, 0.3292830383778838, 0.04331306568741722],
  [0.06909728935823199, 0.919540395075459, 0.011362315566309157],
  [0.016391438875150228, 0.08801330787722578, 0.895595253247624],
] as const;
const rec2020ToRec709 = [
  [1.6604910021084347, -0.5876411387885495, -0.07284986331988486],
  [-0.12455047452159052, 1.1328998971259598, -0.008349422604369487],
  [-0.01815076335490522, -0.10057889800800736, 1.1187296613629125],
] as const;
// AgX inset and outset matrices (in Rec. 2020) as published by Filament (google/filament PR 7236,
// from Blender's AgX); the outset is the inverse of Filament's AgXOutsetMatrixInv, as three.js
// writes it. Row-major here; every row sums to 1, so greys stay grey.
const agxInset = [
  [0.856627153315983, 0.0951212405381588, 0.0482516061458583],
  [0.137318972929847, 0.761241990602591, 0.101439036467562],
  [0.11189821299995, 0.0767994186031903, 0.811302368396859],
] as const;
const agxOutset = [
  [1.1271005818144368, -0.11060664309660323, -0.016493938717834573],
  [-0.1413297634984383, 1.157823702216272, -0.016493938717834257],
  [-0.14132976349843826, -0.11060664309660294, 1.2519364065950405],
] as const;
/** Log2 encoding range: 10 stops below to 6.5 stops above middle grey 0.18 (AgX's LOG2_MIN/MAX). */
export const agxMinEv = Math.log2(0.18) - 10;
export const agxMaxEv = Math.log2(0.18) + 6.5;

function mul3(m: readonly (readonly number[])[], v: readonly number[]): Rgb {
  return [
    m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2],
    m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
    m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2],
  ];
}

/**
 * The AgX base contrast sigmoid as the 6th-order polynomial fit of Benjamin Wrensch's "Minimal AgX
 * implementation" (iolite-engine.com/blog_posts/minimal_agx_implementation; mean squared error
 * 3.67e-6 against Blender's LUT), on the log-encoded value x in [0, 1].
 */
export function agxContrastApprox(x: number): number {
  const x2 = x * x;
  const x4 = x2 * x2;
  return 15.5 * x4 * x2 - 40.14 * x4 * x + 31.96 * x4 - 6.868 * x2 * x + 0.4298 * x2 + 0.1191 * x - 0.00232;
}

/**
 * AgX (Troy Sobotka's AgX, Blender 4.x's default view) as three.js r187's `AgXToneMapping`, which
 * follows Filament: linear sRGB -> Rec. 2020 -> inset -> log2 between agxMinEv and agxMaxEv,
 * clamped to [0, 1] -> sigmoid -> outset -> 2.2 power (the sigmoid's output is display-encoded)
 * -> Rec. 709 -> clamp to [0, 1]. Output is display-referred linear sRGB, like the other modes.
 * Differences from Blender: the polynomial replaces Blender's sigmoid LUT, and no "look" is applied.
 */
export function toneMapAgx(rgb: RgbInput): Rgb {
  const inset = mul3(agxInset, mul3(rec709ToRec2020, rgb));
  const encoded = inset.map((v) => {
    const log = (Math.log2(Math.max(v, 1e-10)) - agxMinEv) / (agxMaxEv - agxMinEv);
    return agxContrastApprox(clamp01(log));
  });
  const outset = mul3(agxOutset, encoded);
  const linear = outset.map((v) => Math.pow(Math.max(v, 0), 2.2));
  const out = mul3(rec2020ToRec709, linear);
  return [clamp01(out[0]), clamp01(out[1]), clamp01(out[2])];
}

/** Display-referred linear RGB in [0, 1]; exposure is applied by the caller before this. */
export function applyToneMapping(rgb: RgbInput, mode: ToneMappingMode): Rgb {
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
    case 'agx':
      mapped = toneMapAgx(x);
      break;
    default:
      throw new GpuRendererError('INVALID_OPTION', `unknown tone mapping ${JSON.stringify(mode)} (expected ${toneMappingNames.join(', ')})`, {
        field: 'toneMapping',
      });
  }
  return [clamp01(mapped[0]), clamp01(mapped[1]), clamp01(mapped[2])];
}

export interface EncodeRadianceOptions {
  /** Default 'neutral'. */
  toneMapping?: ToneMappingMode;
  /** Linear multiplier applied to radiance before tone mapping; default 1. */
  exposure?: number;
  /** Exposure in stops (EV): radiance is multiplied by 2^exposureEv as well; default 0. */
  exposureEv?: number;
}

/**
 * The linear factor radiance is multiplied by before tone mapping: exposure * 2^exposureEv
 * (+1 EV doubles, -1 EV halves). Throws a typed error for a negative or non-finite exposure or a
 * non-finite exposureEv.
 */
export function exposureMultiplier(options: { exposure?: number; exposureEv?: number } = {}): number {
  const exposure = options.exposure ?? 1;
  if (typeof exposure !== 'number' || !Number.isFinite(exposure) || exposure < 0) {
    throw new GpuRendererError('INVALID_OPTION', `expected a finite number >= 0, got ${String(exposure)}`, { field: 'exposure' });
  }
  const ev = options.exposureEv ?? 0;
  if (typeof ev !== 'number' || !Number.isFinite(ev)) {
    throw new GpuRendererError('INVALID_OPTION', `expected a finite number of stops, got ${String(ev)}`, { field: 'exposureEv' });
  }
  return exposure * 2 ** ev;
}

/**
 * Linear RGBA radiance (alpha ignored) -> tone-mapped sRGB RGBA8 with opaque alpha. Quantisation
 * rounds to nearest as WGSL's pack4x8unorm does (floor(0.5 + 255 x)). Non-finite radiance values
 * (which the renderer never produces; it drops and counts invalid samples) encode as 0.
 */
export function encodeRadianceToRgba8(radiance: Float32Array, options: EncodeRadianceOptions = {}): Uint8ClampedArray {
  const mode = options.toneMapping ?? 'neutral';
  if (!isToneMapping(mode)) {
    throw new GpuRendererError('INVALID_OPTION', `unknown tone mapping ${JSON.stringify(mode)} (expected ${toneMappingNames.join(', ')})`, {
      field: 'toneMapping',
    });
  }
  const exposure = exposureMultiplier(options);
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
