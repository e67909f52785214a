/**
 * The RGB response of single wavelengths, for paths that meet a dispersive material
 * (KHR_materials_dispersion): such a path carries one wavelength lambda, drawn uniformly over
 * [SPECTRAL_MIN_NM, SPECTRAL_MAX_NM], and its RGB throughput is multiplied by s(lambda) / pdf.
 * s_c is the linear Rec. 709 colour-matching function of channel c (CIE 1931 2-degree observer,
 * the multi-lobe Gaussian fit of Wyman, Sloan and Shirley 2013, "Simple Analytic Approximations to
 * the CIE XYZ Color Matching Functions", JCGT 2(2), converted with the XYZ -> Rec. 709 matrix),
 * with its negative lobes removed and each channel normalised to integrate to 1: a path whose
 * every interaction is wavelength-independent then keeps its RGB weight in expectation (white
 * stays white), while refraction spreads each channel over its own wavelengths.
 */
import { SPECTRAL_MAX_NM, SPECTRAL_MIN_NM, SPECTRAL_TABLE_NODES } from '../../../gpu-layout/constants.ts';

function lobe(lambda: number, mu: number, below: number, above: number): number {
  const t = (lambda - mu) / (lambda < mu ? below : above);
  return Math.exp(-0.5 * t * t);
}

/** CIE 1931 2-degree colour-matching functions (Wyman et al. 2013, multi-lobe fit). */
export function cieXyz(lambda: number): [number, number, number] {
  const x = 1.056 * lobe(lambda, 599.8, 37.9, 31.0) + 0.362 * lobe(lambda, 442.0, 16.0, 26.7) - 0.065 * lobe(lambda, 501.1, 20.4, 26.2);
  const y = 0.821 * lobe(lambda, 568.8, 46.9, 40.5) + 0.286 * lobe(lambda, 530.9, 16.3, 31.1);
  const z = 1.217 * lobe(lambda, 437.0, 11.8, 36.0) + 0.681 * lobe(lambda, 459.0, 26.0, 13.8);
  return [x, y, z];
}

/** XYZ -> linear Rec. 709 (IEC 61966-2-1), rows. */
const xyzToRec709 = [
  [3.2404542, -1.5371385, -0.4985314],
  [-0.969266, 1.8760108, 0.041556],
  [0.0556434, -0.2040259, 1.0572252],
] as const;

function rawResponse(lambda: number): [number, number, number] {
  const xyz = cieXyz(lambda);
  return xyzToRec709.map((row) => Math.max(0, row[0] * xyz[0] + row[1] * xyz[1] + row[2] * xyz[2])) as [number, number, number];
}

/** Wavelength of table node k. */
export function spectralNode(k: number): number {
  return SPECTRAL_MIN_NM + ((SPECTRAL_MAX_NM - SPECTRAL_MIN_NM) * k) / (SPECTRAL_TABLE_NODES - 1);
}

let table: Float32Array | undefined;

/**
 * RGB response at SPECTRAL_TABLE_NODES wavelengths (rgb + padding per node), scaled so that the
 * piecewise-linear interpolant of each channel integrates to exactly 1 over the range.
 */
export function spectralResponseTable(): Float32Array {
  if (table) return table;
  const n = SPECTRAL_TABLE_NODES;
  const raw = Array.from({ length: n }, (_, k) => rawResponse(spectralNode(k)));
  const step = (SPECTRAL_MAX_NM - SPECTRAL_MIN_NM) / (n - 1);
  const out = new Float32Array(4 * n);
  for (let c = 0; c < 3; c++) {
    let integral = 0;
    for (let k = 0; k + 1 < n; k++) integral += 0.5 * step * (raw[k]![c] + raw[k + 1]![c]);
    for (let k = 0; k < n; k++) out[4 * k + c] = raw[k]![c] / integral;
  }
  table = out;
  return out;
}

/** The interpolated response s(lambda) per nm, as spectral.wesl reads it (0 outside the range). */
export function spectralResponse(lambda: number): [number, number, number] {
  const t = spectralResponseTable();
  const x = ((lambda - SPECTRAL_MIN_NM) / (SPECTRAL_MAX_NM - SPECTRAL_MIN_NM)) * (SPECTRAL_TABLE_NODES - 1);
  if (!(x >= 0 && x <= SPECTRAL_TABLE_NODES - 1)) return [0, 0, 0];
  const k = Math.min(SPECTRAL_TABLE_NODES - 2, Math.floor(x));
  const f = x - k;
  return [0, 1, 2].map((c) => t[4 * k + c]! * (1 - f) + t[4 * (k + 1) + c]! * f) as [number, number, number];
}
