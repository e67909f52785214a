import { requireInteger, requireNumberInRange } from '../errors/validate.ts';
import { FRAUNHOFER_C_TENTHS_NM, FRAUNHOFER_D_TENTHS_NM, FRAUNHOFER_F_TENTHS_NM } from '../gpu-layout/constants.ts';

/**
 * Wavelength samples with their per-wavelength IOR, following KHR_materials_dispersion: the
 * `dispersion` factor is 20 / V, with V the Abbe number V = (n_D - 1) / (n_F - n_C) at the
 * Fraunhofer F, C and D lines, and n(lambda) is the two-term Cauchy fit n = A + B / lambda^2
 * anchored at n(lambda_D) = ior (the KHR_materials_ior value), clamped to at least 1.
 */
// The lines come from the GPU constants, so the kernels' dispersion and this reference use the same ones.
export const fraunhoferLinesNm = Object.freeze({ F: FRAUNHOFER_F_TENTHS_NM / 10, D: FRAUNHOFER_D_TENTHS_NM / 10, C: FRAUNHOFER_C_TENTHS_NM / 10 });

/** Visible range sampled when dispersion is on (CIE 1931 tables are commonly cut to 380-780 nm). */
export const visibleWavelengthRangeNm = Object.freeze({ min: 380, max: 780 });

export interface SpectralSample {
  readonly wavelengthNm: number;
  readonly ior: number;
  /** Monte Carlo weight of this sample; the weights of one call sum to 1. */
  readonly weight: number;
  /** Density of the wavelength choice, per nanometre (0 for the single non-dispersive sample). */
  readonly pdf: number;
}

export interface SpectralSampleOptions {
  /** KHR_materials_ior `ior`, >= 1 (default 1.5). */
  ior?: number;
  /** KHR_materials_dispersion `dispersion`, >= 0 (default 0 = no dispersion). */
  dispersion?: number;
  /** Number of stratified wavelengths when dispersive, 1..64 (default 4). */
  count?: number;
}

/** Abbe number V = 20 / dispersion (infinite, meaning no dispersion, when dispersion is 0). */
export function abbeNumberFromDispersion(dispersion: number): number {
  return dispersion > 0 ? 20 / dispersion : Infinity;
}

/** KHR_materials_dispersion index of refraction at `wavelengthNm`. */
export function dispersiveIor(ior: number, dispersion: number, wavelengthNm: number): number {
  if (!(dispersion > 0)) return ior;
  const { F, C, D } = fraunhoferLinesNm;
  const abbe = abbeNumberFromDispersion(dispersion);
  const b = (ior - 1) / (abbe * (1 / (F * F) - 1 / (C * C)));
  return Math.max(ior + b * (1 / (wavelengthNm * wavelengthNm) - 1 / (D * D)), 1);
}

/**
 * Without dispersion a single sample at lambda_D carries all the weight (no spectral split is
 * needed). With dispersion, `count` stratified wavelengths at the stratum midpoints of the visible
 * range, each with weight 1 / count (uniform pdf 1 / range).
 */
export function createSpectralSamples(options: SpectralSampleOptions = {}): readonly SpectralSample[] {
  const ior = requireNumberInRange(options.ior ?? 1.5, 'ior', { min: 1 });
  const dispersion = requireNumberInRange(options.dispersion ?? 0, 'dispersion', { min: 0 });
  const count = requireInteger(options.count ?? 4, 'count', { min: 1, max: 64 });
  if (dispersion === 0) {
    return Object.freeze([Object.freeze({ wavelengthNm: fraunhoferLinesNm.D, ior, weight: 1, pdf: 0 })]);
  }
  const { min, max } = visibleWavelengthRangeNm;
  const width = (max - min) / count;
  const samples: SpectralSample[] = [];
  for (let i = 0; i < count; i++) {
    const wavelengthNm = min + (i + 0.5) * width;
    samples.push(Object.freeze({ wavelengthNm, ior: dispersiveIor(ior, dispersion, wavelengthNm), weight: 1 / count, pdf: 1 / (max - min) }));
  }
  return Object.freeze(samples);
}
