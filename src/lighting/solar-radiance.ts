import type { Vec3 } from './vec3.ts';

/**
 * Radiance of the solar disc seen through a clear atmosphere, spectrally: a 5778 K black body
 * (whose radiance through the sun's mean solid angle gives the 1361 W/m^2 solar constant) times the
 * direct-beam transmittance exp(-m (tau_R + tau_a)), reduced to linear Rec. 709 RGB with the CIE
 * 1931 2-degree observer:
 * - Rayleigh optical depth tau_R = 0.008735 lambda^-4.08 (lambda in um; Leckner 1978, as used in
 *   Preetham, Shirley, Smits 1999, appendix A.2);
 * - aerosol (Angstrom) tau_a = beta lambda^-1.3 with beta = 0.04608 T - 0.04586 from the turbidity T
 *   (Preetham et al. 1999, appendix A.2), the same turbidity as the Hosek-Wilkie sky;
 * - relative air mass m (Kasten and Young 1989, valid down to the horizon);
 * - ozone and water-vapour absorption are left out (a few per cent, mostly outside the blue).
 * - the colour matching functions are Wyman, Sloan and Shirley's multi-lobe fit (JCGT 2(2), 2013).
 * Output: cd/m^2 per channel convention of this package (683 x CIE-weighted W m^-2 sr^-1), i.e.
 * luminance(rgb) is the disc's luminance in nits.
 */

export const SOLAR_BLACKBODY_KELVIN = 5778;
/** Luminous efficacy constant of the CIE photopic curve, lm/W. */
export const LUMENS_PER_WATT = 683;

function lobe(x: number, mu: number, s1: number, s2: number): number {
  const t = (x - mu) / (x < mu ? s1 : s2);
  return Math.exp(-0.5 * t * t);
}

/** CIE 1931 2-degree colour matching functions at `lambda` nm (Wyman et al. 2013, multi-lobe fit). */
export function cieXyzMatching(lambda: number): Vec3 {
  return [
    1.056 * lobe(lambda, 599.8, 37.9, 31.0) + 0.362 * lobe(lambda, 442.0, 16.0, 26.7) - 0.065 * lobe(lambda, 501.1, 20.4, 26.2),
    0.821 * lobe(lambda, 568.8, 46.9, 40.5) + 0.286 * lobe(lambda, 530.9, 16.3, 31.1),
    1.217 * lobe(lambda, 437.0, 11.8, 36.0) + 0.681 * lobe(lambda, 459.0, 26.0, 13.8),
  ];
}

/** Planck spectral radiance B_lambda(T) in W m^-2 sr^-1 nm^-1. */
export function planckRadiance(lambdaNm: number, kelvin: number): number {
  const h = 6.62607015e-34;
  const c = 299792458;
  const k = 1.380649e-23;
  const l = lambdaNm * 1e-9;
  return (2 * h * c * c) / (l ** 5 * (Math.exp((h * c) / (l * k * kelvin)) - 1)) * 1e-9;
}

/** XYZ (D65 white) to linear Rec. 709 / sRGB primaries (IEC 61966-2-1). */
export function xyzToLinearSrgb(xyz: readonly number[]): Vec3 {
  const [x, y, z] = [xyz[0]!, xyz[1]!, xyz[2]!];
  return [3.2404542 * x - 1.5371385 * y - 0.4985314 * z, -0.969266 * x + 1.8760108 * y + 0.041556 * z, 0.0556434 * x - 0.2040259 * y + 1.0572252 * z];
}

/** Relative optical air mass at solar elevation `elevation` radians (Kasten and Young 1989). */
export function relativeAirMass(elevation: number): number {
  const zenithDeg = 90 - (elevation * 180) / Math.PI;
  return 1 / (Math.sin(elevation) + 0.50572 * Math.pow(96.07995 - zenithDeg, -1.6364));
}

/**
 * RGB radiance of the solar disc (nits per channel) at solar `elevation` (radians, >= 0) through an
 * atmosphere of `turbidity`; `airMass` overrides the path (0 = top of the atmosphere).
 */
export function solarDiscRadiance(elevation: number, turbidity: number, airMass = relativeAirMass(elevation)): Vec3 {
  const beta = Math.max(0, 0.04608 * turbidity - 0.04586);
  const xyz = [0, 0, 0];
  const step = 1;
  for (let lambda = 360; lambda <= 830; lambda += step) {
    const um = lambda / 1000;
    const tau = 0.008735 * Math.pow(um, -4.08) + beta * Math.pow(um, -1.3);
    const l = planckRadiance(lambda, SOLAR_BLACKBODY_KELVIN) * Math.exp(-airMass * tau);
    const cmf = cieXyzMatching(lambda);
    for (let c = 0; c < 3; c++) xyz[c] = xyz[c]! + l * cmf[c]! * step;
  }
  const rgb = xyzToLinearSrgb(xyz);
  // A low sun's deep red spectrum lies outside the Rec. 709 gamut (negative blue): clip the colour
  // to the gamut (radiance cannot be negative; the clipped channel carries almost no luminance).
  return [Math.max(0, rgb[0]) * LUMENS_PER_WATT, Math.max(0, rgb[1]) * LUMENS_PER_WATT, Math.max(0, rgb[2]) * LUMENS_PER_WATT];
}
