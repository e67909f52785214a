/**
 * Validation of the production-output options: adaptive sampling, the denoiser,
 * presentation, submission bounds, feature flags and the per-frame budget. Every error names its field.
 */
import { fail, requireFiniteNumber, requireInteger, requireNumberInRange } from '../errors/validate.ts';
import { defaultAdaptiveSamplingParameters } from '../post/adaptive-sampling/converged-mask.ts';
import { resolveFeatureFlags, type WavefrontFeatureFlagResolution } from './feature-flags.ts';
import type { WavefrontDenoiserName } from '../post/denoise/denoiser.ts';
import type { WavefrontAdaptiveSettings, WavefrontDenoiseOptions, WavefrontDenoiseSettings, WavefrontPresentationOutput, WavefrontProgressListener } from './output-types.ts';

/** Most samples per pixel one renderFrame call takes, and the adaptive prediction's ceiling. */
export const maxSamplesPerFrame = 65536;
/** Default waves (frame passes) per command buffer. */
export const defaultFramePassesPerSubmission = 16;
export const maxFramePassesPerSubmissionLimit = 256;

export const defaultDenoiseSettings: Readonly<WavefrontDenoiseSettings> = Object.freeze({
  denoiser: 'auto',
  present: 'denoised',
  iterations: 5,
  // SVGF uses 4 with temporally accumulated 1-spp variance; with every sample's moments in the film,
  // 2 measured better from 16 spp up and the same at 4 spp (README, Performance).
  sigmaLuminance: 2,
  sigmaNormal: 128,
  sigmaDepth: 1,
  auxiliary: true,
  precision: 'auto',
  emission: 'exact',
  maxMemoryMB: 1024,
  weights: 'rt_hdr_alb_nrm',
});

const atrousOptionNames = ['iterations', 'sigmaLuminance', 'sigmaNormal', 'sigmaDepth'] as const;
const oidnOptionNames = ['auxiliary', 'precision', 'emission', 'maxMemoryMB', 'weights'] as const;

/** The output options as the renderer's creation options carry them. */
export interface WavefrontOutputOptions {
  adaptiveThreshold?: number;
  minimumSamplesPerPixel?: number;
  denoise?: boolean | WavefrontDenoiserName | WavefrontDenoiseOptions;
  exposureEv?: number;
  presentationOutput?: WavefrontPresentationOutput;
  maxFramePassesPerSubmission?: number;
  featureFlags?: Readonly<Record<string, boolean>>;
  onProgress?: WavefrontProgressListener;
}

export interface WavefrontOutputConfig {
  adaptive: WavefrontAdaptiveSettings | null;
  denoise: WavefrontDenoiseSettings | null;
  /** The bytes of user OIDN weights (denoise.weights), else null. */
  denoiseWeights: Uint8Array | null;
  exposureEv: number;
  presentationOutput: WavefrontPresentationOutput;
  maxFramePassesPerSubmission: number;
  features: WavefrontFeatureFlagResolution;
  onProgress: WavefrontProgressListener | null;
}

/** Names of the output options (the renderer's option whitelist includes them). */
export const outputOptionNames: readonly (keyof WavefrontOutputOptions)[] = Object.freeze([
  'adaptiveThreshold', 'minimumSamplesPerPixel', 'denoise', 'exposureEv', 'presentationOutput', 'maxFramePassesPerSubmission', 'featureFlags', 'onProgress',
]);

function parseDenoise(value: unknown): { settings: WavefrontDenoiseSettings; weights: Uint8Array | null } | null {
  if (value === undefined || value === false) return null;
  const d = defaultDenoiseSettings;
  if (value === true) return { settings: { ...d }, weights: null };
  if (value === 'oidn' || value === 'atrous') return { settings: { ...d, denoiser: value }, weights: null };
  if (typeof value !== 'object' || value === null || Array.isArray(value)) fail('INVALID_OPTION', 'denoise', `expected true, false, 'oidn', 'atrous' or an options object, got ${JSON.stringify(value)}`);
  const o = value as Record<string, unknown>;
  const known = ['denoiser', 'present', ...atrousOptionNames, ...oidnOptionNames];
  for (const key of Object.keys(o)) if (!known.includes(key)) fail('INVALID_OPTION', `denoise.${key}`, `unknown denoise option (expected ${known.join(', ')})`);
  const given = (names: readonly string[]) => names.filter((k) => o[k] !== undefined);
  const atrousGiven = given(atrousOptionNames);
  const oidnGiven = given(oidnOptionNames);
  let denoiser = o.denoiser ?? d.denoiser;
  if (denoiser !== 'auto' && denoiser !== 'oidn' && denoiser !== 'atrous') fail('INVALID_OPTION', 'denoise.denoiser', `expected 'oidn', 'atrous' or 'auto', got ${JSON.stringify(denoiser)}`);
  if (atrousGiven.length > 0 && oidnGiven.length > 0) fail('INVALID_OPTION', `denoise.${oidnGiven[0]}`, `applies to the 'oidn' denoiser, but ${atrousGiven[0]} asks for 'atrous'`);
  if (denoiser === 'auto') denoiser = atrousGiven.length > 0 ? 'atrous' : oidnGiven.length > 0 ? 'oidn' : 'auto';
  const wrong = denoiser === 'oidn' ? atrousGiven : denoiser === 'atrous' ? oidnGiven : [];
  if (wrong.length > 0) fail('INVALID_OPTION', `denoise.${wrong[0]}`, `does not apply to the '${String(denoiser)}' denoiser`);
  const present = o.present ?? d.present;
  if (present !== 'denoised' && present !== 'raw') fail('INVALID_OPTION', 'denoise.present', `expected 'denoised' or 'raw', got ${JSON.stringify(present)}`);
  const positive = (key: string, fallback: number): number => {
    const v = o[key] === undefined ? fallback : requireFiniteNumber(o[key], `denoise.${key}`);
    if (!(v > 0)) fail('INVALID_OPTION', `denoise.${key}`, `must be > 0, got ${v}`);
    return v;
  };
  if (o.auxiliary !== undefined && typeof o.auxiliary !== 'boolean') fail('INVALID_OPTION', 'denoise.auxiliary', `expected a boolean, got ${JSON.stringify(o.auxiliary)}`);
  const precision = o.precision ?? d.precision;
  if (precision !== 'auto' && precision !== 'f16' && precision !== 'f32') fail('INVALID_OPTION', 'denoise.precision', `expected 'auto', 'f16' or 'f32', got ${JSON.stringify(precision)}`);
  const emission = o.emission ?? d.emission;
  if (emission !== 'exact' && emission !== 'network') fail('INVALID_OPTION', 'denoise.emission', `expected 'exact' or 'network', got ${JSON.stringify(emission)}`);
  let weights: Uint8Array | null = null;
  if (o.weights !== undefined) {
    if (o.weights instanceof ArrayBuffer) weights = new Uint8Array(o.weights.slice(0));
    else if (ArrayBuffer.isView(o.weights)) weights = new Uint8Array(o.weights.buffer.slice(o.weights.byteOffset, o.weights.byteOffset + o.weights.byteLength));
    else fail('INVALID_OPTION', 'denoise.weights', 'expected the bytes of an OIDN .tza file (ArrayBuffer or typed array)');
    if (o.auxiliary !== undefined) fail('INVALID_OPTION', 'denoise.auxiliary', 'the weights decide the inputs: give either weights or auxiliary');
  }
  const auxiliary = (o.auxiliary as boolean | undefined) ?? d.auxiliary;
  return {
    settings: {
      denoiser: denoiser as WavefrontDenoiseSettings['denoiser'],
      present,
      iterations: o.iterations === undefined ? d.iterations : requireInteger(o.iterations, 'denoise.iterations', { min: 1, max: 8 }),
      sigmaLuminance: positive('sigmaLuminance', d.sigmaLuminance),
      sigmaNormal: o.sigmaNormal === undefined ? d.sigmaNormal : requireNumberInRange(o.sigmaNormal, 'denoise.sigmaNormal', { min: 0, max: 1024 }),
      sigmaDepth: positive('sigmaDepth', d.sigmaDepth),
      auxiliary,
      precision,
      emission,
      maxMemoryMB: o.maxMemoryMB === undefined ? d.maxMemoryMB : requireNumberInRange(o.maxMemoryMB, 'denoise.maxMemoryMB', { min: 16, max: 1 << 20 }),
      weights: weights ? 'custom' : auxiliary ? 'rt_hdr_alb_nrm' : 'rt_hdr',
    },
    weights,
  };
}

/** Validates the output options; defaults for everything omitted. */
export function parseOutputOptions(options: WavefrontOutputOptions): WavefrontOutputConfig {
  let adaptive: WavefrontAdaptiveSettings | null = null;
  if (options.adaptiveThreshold !== undefined) {
    const threshold = requireFiniteNumber(options.adaptiveThreshold, 'adaptiveThreshold');
    if (!(threshold > 0)) fail('INVALID_OPTION', 'adaptiveThreshold', `must be > 0, got ${threshold}`);
    // The error compares the mean of all samples with that of the even-indexed half: two at least.
    const minimumSamplesPerPixel =
      options.minimumSamplesPerPixel === undefined
        ? defaultAdaptiveSamplingParameters(1, threshold).minimumSamplesPerPixel
        : requireInteger(options.minimumSamplesPerPixel, 'minimumSamplesPerPixel', { min: 2, max: maxSamplesPerFrame });
    adaptive = { threshold, minimumSamplesPerPixel };
  } else if (options.minimumSamplesPerPixel !== undefined) {
    fail('INVALID_OPTION', 'minimumSamplesPerPixel', 'applies to adaptive sampling: set adaptiveThreshold too (or pass it to renderFrame with frameTimeBudgetMs)');
  }
  const exposureEv = options.exposureEv === undefined ? 0 : requireNumberInRange(options.exposureEv, 'exposureEv', { min: -64, max: 64 });
  const presentationOutput = options.presentationOutput ?? 'tonemapped';
  if (presentationOutput !== 'tonemapped' && presentationOutput !== 'linear') {
    fail('INVALID_OPTION', 'presentationOutput', `expected 'tonemapped' or 'linear', got ${JSON.stringify(presentationOutput)}`);
  }
  const maxFramePassesPerSubmission =
    options.maxFramePassesPerSubmission === undefined
      ? defaultFramePassesPerSubmission
      : requireInteger(options.maxFramePassesPerSubmission, 'maxFramePassesPerSubmission', { min: 1, max: maxFramePassesPerSubmissionLimit });
  if (options.onProgress !== undefined && typeof options.onProgress !== 'function') fail('INVALID_OPTION', 'onProgress', 'expected a function');
  const denoise = parseDenoise(options.denoise);
  return {
    adaptive,
    denoise: denoise?.settings ?? null,
    denoiseWeights: denoise?.weights ?? null,
    exposureEv,
    presentationOutput,
    maxFramePassesPerSubmission,
    features: resolveFeatureFlags(options.featureFlags),
    onProgress: options.onProgress ?? null,
  };
}

/** renderFrame / renderOnce options. */
export interface WavefrontRenderFrameOptions {
  /** Samples per pixel of this call (a ceiling when frameTimeBudgetMs is given); default the renderer's. */
  samplesPerPixel?: number;
  /**
   * Time budget of the call in ms: after the minimum the renderer adds one sample pass at a time
   * while the measured pass time still fits (it waits for the GPU between passes).
   */
  frameTimeBudgetMs?: number;
  /** With frameTimeBudgetMs: sample passes the call always renders; default 1. */
  minimumSamplesPerPixel?: number;
  /** Called after every group of passes and at the end (besides the renderer's 'progress' events). */
  onProgress?: WavefrontProgressListener;
}

export interface ParsedFrameOptions {
  ceiling: number;
  budgetMs: number | null;
  minimum: number;
  onProgress: WavefrontProgressListener | null;
}

export function parseRenderFrameOptions(options: WavefrontRenderFrameOptions | undefined, defaultSamples: number): ParsedFrameOptions {
  if (options === undefined) return { ceiling: defaultSamples, budgetMs: null, minimum: defaultSamples, onProgress: null };
  if (typeof options !== 'object' || options === null) fail('INVALID_OPTION', 'options', 'expected an options object');
  const known = ['samplesPerPixel', 'frameTimeBudgetMs', 'minimumSamplesPerPixel', 'onProgress'];
  for (const key of Object.keys(options)) if (!known.includes(key)) fail('INVALID_OPTION', key, 'unknown renderFrame option');
  const ceiling = options.samplesPerPixel === undefined ? defaultSamples : requireInteger(options.samplesPerPixel, 'samplesPerPixel', { min: 1, max: maxSamplesPerFrame });
  let budgetMs: number | null = null;
  if (options.frameTimeBudgetMs !== undefined) {
    budgetMs = requireFiniteNumber(options.frameTimeBudgetMs, 'frameTimeBudgetMs');
    if (!(budgetMs > 0)) fail('INVALID_OPTION', 'frameTimeBudgetMs', `must be > 0, got ${budgetMs}`);
  }
  let minimum = ceiling;
  if (options.minimumSamplesPerPixel !== undefined) {
    if (budgetMs === null) fail('INVALID_OPTION', 'minimumSamplesPerPixel', 'applies with frameTimeBudgetMs (the guaranteed floor of a budgeted frame)');
    minimum = requireInteger(options.minimumSamplesPerPixel, 'minimumSamplesPerPixel', { min: 1, max: ceiling });
  } else if (budgetMs !== null) {
    minimum = 1;
  }
  if (options.onProgress !== undefined && typeof options.onProgress !== 'function') fail('INVALID_OPTION', 'onProgress', 'expected a function');
  return { ceiling, budgetMs, minimum, onProgress: options.onProgress ?? null };
}
