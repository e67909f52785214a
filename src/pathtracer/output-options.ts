/**
 * Validation of the production-output options: adaptive sampling, the denoiser,
 * presentation, submission bounds, feature flags and the per-frame budget. Every error names its field.
 */
import { fail, requireFiniteNumber, requireInteger, requireNumberInRange } from '../errors/validate.ts';
import { defaultAdaptiveSamplingParameters } from '../film/adaptive/converged-mask.ts';
import { resolveFeatureFlags, type WavefrontFeatureFlagResolution } from './feature-flags.ts';
import type { WavefrontDenoiserName } from '../film/denoise/denoiser.ts';
import type { WavefrontAdaptiveSettings, WavefrontDenoiseOptions, WavefrontDenoiseSettings, WavefrontPresentationOutput, WavefrontProgressListener } from './output-types.ts';

import { maxSamplesPerFrame } from '../film/adaptive/settings.ts';
import { parseDenoiseOptions } from '../film/denoise/options.ts';

export { maxSamplesPerFrame } from '../film/adaptive/settings.ts';
export { defaultDenoiseSettings } from '../film/denoise/options.ts';
/** Default waves (frame passes) per command buffer. */
export const defaultFramePassesPerSubmission = 16;
export const maxFramePassesPerSubmissionLimit = 256;

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
  const denoise = parseDenoiseOptions(options.denoise);
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
