/**
 * validateWavefrontDenoise: the acceptance check that keeps denoising reviewable. Given a converged
 * reference, the raw (denoise-off) render and the denoised render of the same frame, it measures
 * four criteria and compares each with a threshold:
 *
 * - structuralArtifacts: edges the denoiser introduced that the reference does not have (tile
 *   seams, blotches, ringing away from real edges), in the gradient domain of luminance;
 * - invalidSamples: NaN/Inf samples the renderer dropped plus non-finite pixels in either image;
 * - baselineNoise: the raw image's relative MSE against the reference, so validation stays honest
 *   about the noise level with the denoiser off;
 * - detailRetention (per named region, e.g. sheen, chrome, wood): how much of the reference's
 *   high-frequency detail the denoised image keeps.
 *
 * All measurements use linear Rec. 709 luminance (0.2126 R + 0.7152 G + 0.0722 B); non-finite
 * values count as invalid and are read as 0 for the other measurements.
 */
import { GpuRendererError } from '../../errors/gpu-renderer-error.ts';
import { requireLinearRgbaImage, type LinearRgbaImage } from '../../io/images/linear-image.ts';
import { gaussianBlur } from '../metrics/gaussian-blur.ts';

export interface DenoiseValidationRegion {
  /** Names the criterion `detailRetention.<name>`, e.g. 'sheen', 'chrome', 'wood'. */
  name: string;
  x: number;
  y: number;
  width: number;
  height: number;
  /** Overrides thresholds.minDetailRetention for this region. */
  minDetailRetention?: number;
}

export interface DenoiseValidationInput {
  /** Converged render of the frame (many samples, no denoiser). */
  reference: LinearRgbaImage;
  /** The validated render with the denoiser off. */
  raw: LinearRgbaImage;
  /** The same render after the denoiser. */
  denoised: LinearRgbaImage;
  /** Samples the renderer dropped as NaN/Inf (frame stats radianceDiagnostics.invalidSamples). */
  invalidSamples: number;
  /** Detail-retention regions; default one region, 'frame', covering the image. */
  regions?: readonly DenoiseValidationRegion[];
}

export interface DenoiseValidationThresholds {
  /** Largest structural-artifact score (see README); default 0.02. */
  maxStructuralArtifact: number;
  /** Largest number of invalid samples and pixels; default 0. */
  maxInvalidSamples: number;
  /** Largest relative MSE of the raw image against the reference; default 0.02. */
  maxBaselineRelativeMse: number;
  /** Smallest share of the reference's detail the denoised image keeps; default 0.8. */
  minDetailRetention: number;
}

export const defaultDenoiseValidationThresholds: Readonly<DenoiseValidationThresholds> = Object.freeze({
  maxStructuralArtifact: 0.02,
  maxInvalidSamples: 0,
  maxBaselineRelativeMse: 0.02,
  minDetailRetention: 0.8,
});

export interface DenoiseValidationCriterion {
  /** `structuralArtifacts`, `invalidSamples`, `baselineNoise` or `detailRetention.<region>`. */
  id: string;
  measured: number;
  threshold: number;
  /** How measured must relate to threshold to pass. */
  comparison: '<=' | '>=';
  passed: boolean;
  /** Supporting measurements (not compared with thresholds). */
  details: Readonly<Record<string, number>>;
}

export interface DenoiseValidationReport {
  passed: boolean;
  criteria: readonly DenoiseValidationCriterion[];
  structuralArtifacts: DenoiseValidationCriterion;
  invalidSamples: DenoiseValidationCriterion;
  baselineNoise: DenoiseValidationCriterion;
  detailRetention: Readonly<Record<string, DenoiseValidationCriterion>>;
  thresholds: Readonly<DenoiseValidationThresholds>;
}

/** Pre-blur sigma that suppresses residual per-pixel noise before gradients are compared. */
export const structuralPreBlurSigma = 1;
/** Radius of the neighbourhood whose strongest reference edge excuses a denoised edge (blur spread). */
export const structuralEdgeToleranceRadius = 2;
/** Number of rows (columns) the error's x- (y-) gradient is averaged over: the coherence length of an artifact edge. */
export const structuralCoherenceLength = 8;
/** Sigma of the low-pass whose residual is the "detail" (high-frequency) band. */
export const detailBandSigma = 1.5;
/** Epsilon of the relative MSE (as in metrics/relativeMeanSquaredError). */
const relativeMseEpsilon = 0.01;

function fail(field: string, message: string): never {
  throw new GpuRendererError('INVALID_OPTION', message, { field });
}

function luminance(image: LinearRgbaImage): { y: Float64Array; nonFinite: number } {
  const n = image.width * image.height;
  const y = new Float64Array(n);
  let nonFinite = 0;
  for (let p = 0; p < n; p++) {
    const r = image.data[4 * p];
    const g = image.data[4 * p + 1];
    const b = image.data[4 * p + 2];
    if (!Number.isFinite(r) || !Number.isFinite(g) || !Number.isFinite(b)) {
      nonFinite++;
      continue;
    }
    y[p] = 0.2126 * r + 0.7152 * g + 0.0722 * b;
  }
  return { y, nonFinite };
}

/** |forward-difference gradient| per pixel (the missing neighbour at the right/bottom edge counts as 0 difference). */
function gradientMagnitude(y: Float64Array, w: number, h: number): Float64Array {
  const out = new Float64Array(w * h);
  for (let j = 0; j < h; j++) {
    for (let i = 0; i < w; i++) {
      const p = j * w + i;
      const gx = i + 1 < w ? y[p + 1] - y[p] : 0;
      const gy = j + 1 < h ? y[p + w] - y[p] : 0;
      out[p] = Math.sqrt(gx * gx + gy * gy);
    }
  }
  return out;
}

function maxFilter(src: Float64Array, w: number, h: number, radius: number): Float64Array {
  const rows = new Float64Array(w * h);
  for (let j = 0; j < h; j++) {
    for (let i = 0; i < w; i++) {
      let m = 0;
      for (let k = Math.max(0, i - radius); k <= Math.min(w - 1, i + radius); k++) m = Math.max(m, src[j * w + k]);
      rows[j * w + i] = m;
    }
  }
  const out = new Float64Array(w * h);
  for (let j = 0; j < h; j++) {
    for (let i = 0; i < w; i++) {
      let m = 0;
      for (let k = Math.max(0, j - radius); k <= Math.min(h - 1, j + radius); k++) m = Math.max(m, rows[k * w + i]);
      out[j * w + i] = m;
    }
  }
  return out;
}

function mean(values: Float64Array): number {
  let s = 0;
  for (let i = 0; i < values.length; i++) s += values[i];
  return s / values.length;
}

/**
 * Largest coherent error edge not explained by a reference edge, over the reference's mean
 * luminance. The error e = Y_denoised - Y_reference is pre-blurred (Gaussian, sigma 1) to suppress
 * residual per-pixel noise; its x-gradient is averaged over 8 rows and its y-gradient over 8
 * columns, so edges that run along a line or bound an area (tile seams, blotches) keep their
 * strength while incoherent noise averages away; reference edges within 2 pixels (the strongest
 * |grad Y_reference~| in a 5x5 neighbourhood) are subtracted, so blur spread and ringing at real
 * edges are left to the detail criterion.
 */
function structuralArtifactScore(denoised: Float64Array, reference: Float64Array, w: number, h: number): { score: number; worstX: number; worstY: number } {
  const error = gaussianBlur(
    denoised.map((v, i) => v - reference[i]),
    w,
    h,
    structuralPreBlurSigma,
  );
  const referenceEdges = maxFilter(gradientMagnitude(gaussianBlur(reference, w, h, structuralPreBlurSigma), w, h), w, h, structuralEdgeToleranceRadius);
  const half = structuralCoherenceLength / 2;
  let worst = 0;
  let worstX = 0;
  let worstY = 0;
  for (let j = 0; j < h; j++) {
    for (let i = 0; i < w; i++) {
      let gx = 0;
      let gy = 0;
      let nx = 0;
      let ny = 0;
      for (let k = -half + 1; k <= half; k++) {
        const jj = j + k;
        if (i + 1 < w && jj >= 0 && jj < h) {
          gx += error[jj * w + i + 1] - error[jj * w + i];
          nx++;
        }
        const ii = i + k;
        if (j + 1 < h && ii >= 0 && ii < w) {
          gy += error[(j + 1) * w + ii] - error[j * w + ii];
          ny++;
        }
      }
      const coherent = Math.hypot(nx > 0 ? gx / nx : 0, ny > 0 ? gy / ny : 0);
      const excess = coherent - referenceEdges[j * w + i];
      if (excess > worst) {
        worst = excess;
        worstX = i;
        worstY = j;
      }
    }
  }
  const scale = mean(reference);
  return { score: scale > 0 ? worst / scale : worst > 0 ? Infinity : 0, worstX, worstY };
}

function relativeMse(test: LinearRgbaImage, reference: LinearRgbaImage): number {
  let sum = 0;
  const n = reference.width * reference.height;
  for (let i = 0; i < 4 * n; i++) {
    if (i % 4 === 3) continue;
    const r = Number.isFinite(reference.data[i]) ? reference.data[i] : 0;
    const t = Number.isFinite(test.data[i]) ? test.data[i] : 0;
    sum += ((t - r) * (t - r)) / (r * r + relativeMseEpsilon);
  }
  return sum / (3 * n);
}

/**
 * <HF_test, HF_ref> / <HF_ref, HF_ref> over a region, HF = Y - GaussianBlur(Y, 1.5): the share of the
 * reference's detail present in the test image (noise uncorrelated with it adds nothing on
 * average). NaN, which fails, when the reference has no detail there (RMS band below 1e-6 of the
 * mean luminance).
 */
function detailProjection(testBand: Float64Array, referenceBand: Float64Array, w: number, region: DenoiseValidationRegion, meanLuminance: number): { retention: number; referenceEnergy: number } {
  let cross = 0;
  let energy = 0;
  for (let j = region.y; j < region.y + region.height; j++) {
    for (let i = region.x; i < region.x + region.width; i++) {
      const p = j * w + i;
      cross += testBand[p] * referenceBand[p];
      energy += referenceBand[p] * referenceBand[p];
    }
  }
  const count = region.width * region.height;
  const measurable = energy / count > (1e-6 * meanLuminance) ** 2;
  return { retention: measurable ? cross / energy : Number.NaN, referenceEnergy: energy / count };
}

function criterion(id: string, measured: number, threshold: number, comparison: '<=' | '>=', details: Record<string, number> = {}): DenoiseValidationCriterion {
  // NaN never passes.
  const passed = comparison === '<=' ? measured <= threshold : measured >= threshold;
  return Object.freeze({ id, measured, threshold, comparison, passed, details: Object.freeze(details) });
}

function resolveThresholds(overrides: Partial<DenoiseValidationThresholds>): DenoiseValidationThresholds {
  const t = { ...defaultDenoiseValidationThresholds, ...overrides };
  for (const key of Object.keys(defaultDenoiseValidationThresholds) as (keyof DenoiseValidationThresholds)[]) {
    const v = t[key];
    if (typeof v !== 'number' || !Number.isFinite(v) || v < 0) fail(`thresholds.${key}`, `expected a finite number >= 0, got ${String(v)}`);
  }
  return t;
}

function resolveRegions(regions: readonly DenoiseValidationRegion[] | undefined, w: number, h: number): DenoiseValidationRegion[] {
  if (regions === undefined) return [{ name: 'frame', x: 0, y: 0, width: w, height: h }];
  if (!Array.isArray(regions) || regions.length === 0) fail('regions', 'expected a non-empty array of regions');
  const names = new Set<string>();
  return regions.map((r, i) => {
    const field = `regions[${i}]`;
    if (typeof r?.name !== 'string' || r.name === '' || names.has(r.name)) fail(`${field}.name`, 'expected a unique non-empty name');
    names.add(r.name);
    for (const key of ['x', 'y', 'width', 'height'] as const) {
      if (!Number.isInteger(r[key]) || r[key] < 0) fail(`${field}.${key}`, `expected an integer >= 0, got ${String(r[key])}`);
    }
    if (r.width < 1 || r.height < 1 || r.x + r.width > w || r.y + r.height > h) fail(field, `expected a non-empty rectangle inside the ${w}x${h} image`);
    if (r.minDetailRetention !== undefined && !(Number.isFinite(r.minDetailRetention) && r.minDetailRetention >= 0)) {
      fail(`${field}.minDetailRetention`, 'expected a finite number >= 0');
    }
    return r;
  });
}

/** Measures the four denoise acceptance criteria; see the module comment and the README for their definitions. */
export function validateWavefrontDenoise(input: DenoiseValidationInput, thresholds: Partial<DenoiseValidationThresholds> = {}): DenoiseValidationReport {
  if (input === null || typeof input !== 'object') fail('input', 'expected { reference, raw, denoised, invalidSamples }');
  requireLinearRgbaImage(input.reference, 'reference');
  const { width: w, height: h } = input.reference;
  for (const key of ['raw', 'denoised'] as const) {
    requireLinearRgbaImage(input[key], key);
    if (input[key].width !== w || input[key].height !== h) fail(key, `expected ${w}x${h} like the reference`);
  }
  if (!Number.isInteger(input.invalidSamples) || input.invalidSamples < 0) fail('invalidSamples', `expected an integer >= 0, got ${String(input.invalidSamples)}`);
  const limits = resolveThresholds(thresholds ?? {});
  const regions = resolveRegions(input.regions, w, h);

  const reference = luminance(input.reference);
  const raw = luminance(input.raw);
  const denoised = luminance(input.denoised);

  const artifacts = structuralArtifactScore(denoised.y, reference.y, w, h);
  const structuralArtifacts = criterion('structuralArtifacts', artifacts.score, limits.maxStructuralArtifact, '<=', {
    worstX: artifacts.worstX,
    worstY: artifacts.worstY,
  });

  const invalidTotal = input.invalidSamples + raw.nonFinite + denoised.nonFinite;
  const invalidSamples = criterion('invalidSamples', invalidTotal, limits.maxInvalidSamples, '<=', {
    droppedSamples: input.invalidSamples,
    nonFiniteRawPixels: raw.nonFinite,
    nonFiniteDenoisedPixels: denoised.nonFinite,
    nonFiniteReferencePixels: reference.nonFinite,
  });

  const rawRelMse = relativeMse(input.raw, input.reference);
  const denoisedRelMse = relativeMse(input.denoised, input.reference);
  const baselineNoise = criterion('baselineNoise', rawRelMse, limits.maxBaselineRelativeMse, '<=', {
    denoisedRelativeMse: denoisedRelMse,
    denoiserErrorReduction: denoisedRelMse > 0 ? rawRelMse / denoisedRelMse : Infinity,
  });

  const band = (y: Float64Array): Float64Array => {
    const low = gaussianBlur(y, w, h, detailBandSigma);
    return y.map((v, i) => v - low[i]);
  };
  const referenceBand = band(reference.y);
  const referenceMean = mean(reference.y);
  const denoisedBand = band(denoised.y);
  const rawBand = band(raw.y);
  const detailRetention: Record<string, DenoiseValidationCriterion> = {};
  for (const region of regions) {
    const kept = detailProjection(denoisedBand, referenceBand, w, region, referenceMean);
    const rawKept = detailProjection(rawBand, referenceBand, w, region, referenceMean);
    detailRetention[region.name] = criterion(`detailRetention.${region.name}`, kept.retention, region.minDetailRetention ?? limits.minDetailRetention, '>=', {
      rawRetention: rawKept.retention,
      referenceDetailEnergy: kept.referenceEnergy,
    });
  }

  const criteria = [structuralArtifacts, invalidSamples, baselineNoise, ...Object.values(detailRetention)];
  return Object.freeze({
    passed: criteria.every((c) => c.passed),
    criteria: Object.freeze(criteria),
    structuralArtifacts,
    invalidSamples,
    baselineNoise,
    detailRetention: Object.freeze(detailRetention),
    thresholds: Object.freeze(limits),
  });
}
