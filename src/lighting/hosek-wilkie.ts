import {
  HOSEK_WILKIE_RGB_1,
  HOSEK_WILKIE_RGB_2,
  HOSEK_WILKIE_RGB_3,
  HOSEK_WILKIE_RGB_RADIANCE_1,
  HOSEK_WILKIE_RGB_RADIANCE_2,
  HOSEK_WILKIE_RGB_RADIANCE_3,
} from './hosek-wilkie-rgb-data.ts';
import type { Vec3 } from './vec3.ts';

/**
 * The Hosek-Wilkie clear-sky model (Hosek and Wilkie 2012, "An Analytic Model for Full Spectral
 * Sky-Dome Radiance", ACM TOG 31(4), eq. 9), RGB version. For a view direction at angle theta from
 * the zenith and gamma from the sun:
 *   F(theta, gamma) = (1 + A exp(B / (cos theta + 0.01))) *
 *                     (C + D exp(E gamma) + F cos^2 gamma + G chi(H, gamma) + I sqrt(cos theta)),
 *   chi(g, a) = (1 + cos^2 a) / (1 + g^2 - 2 g cos a)^(3/2),
 *   L = F(theta, gamma) * L_M,
 * with the nine parameters and L_M interpolated from the fitted tables: quintic Bezier in
 * (solar elevation / (pi / 2))^(1/3), linearly in turbidity (1..10) and ground albedo (0..1).
 * Output units are those of the published RGB data: linear sRGB / Rec. 709 primaries, radiometric
 * (W m^-2 sr^-1) weighted by the CIE 1931 matching functions, so 683 x luminance(L) is cd/m^2
 * (the dataset's version notes). The solar disc is not part of the sky radiance.
 */
export interface HosekWilkieSky {
  /** Per channel, the nine parameters (A..I in the dataset's order). */
  readonly config: readonly (readonly number[])[];
  /** Per channel, the radiance scale L_M. */
  readonly radiance: Vec3;
  readonly turbidity: number;
  readonly albedo: Vec3;
  readonly solarElevation: number;
}

const DATASETS = [HOSEK_WILKIE_RGB_1, HOSEK_WILKIE_RGB_2, HOSEK_WILKIE_RGB_3];
const RADIANCE_DATASETS = [HOSEK_WILKIE_RGB_RADIANCE_1, HOSEK_WILKIE_RGB_RADIANCE_2, HOSEK_WILKIE_RGB_RADIANCE_3];

/** Quintic Bezier (Bernstein) weights at t. */
function bernstein5(t: number): number[] {
  const s = 1 - t;
  return [s ** 5, 5 * s ** 4 * t, 10 * s ** 3 * t ** 2, 10 * s ** 2 * t ** 3, 5 * s * t ** 4, t ** 5];
}

/**
 * Interpolates one table entry set: `stride` values per control point, at (turbidity, albedo,
 * elevation), as the reference implementation's CookConfiguration / CookRadianceConfiguration.
 */
function cook(dataset: readonly number[], stride: number, turbidity: number, albedo: number, elevation: number): number[] {
  const weights = bernstein5(Math.cbrt(elevation / (Math.PI / 2)));
  const t0 = Math.min(Math.floor(turbidity), 10);
  const tRem = turbidity - t0;
  const perTurbidity = stride * 6;
  const perAlbedo = perTurbidity * 10;
  const out = new Array<number>(stride).fill(0);
  const add = (albedoIndex: number, t: number, w: number): void => {
    if (w === 0) return;
    const base = albedoIndex * perAlbedo + (t - 1) * perTurbidity;
    for (let i = 0; i < stride; i++) {
      let v = 0;
      for (let k = 0; k < 6; k++) v += weights[k]! * dataset[base + k * stride + i]!;
      out[i] = out[i]! + w * v;
    }
  };
  add(0, t0, (1 - albedo) * (1 - tRem));
  add(1, t0, albedo * (1 - tRem));
  if (t0 < 10) {
    add(0, t0 + 1, (1 - albedo) * tRem);
    add(1, t0 + 1, albedo * tRem);
  }
  return out;
}

/** The model state for a sun at `solarElevation` radians (0..pi/2), turbidity 1..10, albedo 0..1 per channel. */
export function createHosekWilkieSky(turbidity: number, albedo: readonly number[], solarElevation: number): HosekWilkieSky {
  const config = DATASETS.map((d, c) => cook(d, 9, turbidity, albedo[c]!, solarElevation));
  const radiance = RADIANCE_DATASETS.map((d, c) => cook(d, 1, turbidity, albedo[c]!, solarElevation)[0]!) as Vec3;
  return { config, radiance, turbidity, albedo: [albedo[0]!, albedo[1]!, albedo[2]!], solarElevation };
}

/** Sky radiance for a view at `theta` from the zenith (< pi/2) and `gamma` from the sun. */
export function hosekWilkieRadiance(sky: HosekWilkieSky, theta: number, gamma: number): Vec3 {
  const cosTheta = Math.max(0, Math.cos(theta));
  const cosGamma = Math.cos(gamma);
  const out: Vec3 = [0, 0, 0];
  for (let c = 0; c < 3; c++) {
    const [A, B, C, D, E, F, G, I, H] = sky.config[c]! as [number, number, number, number, number, number, number, number, number];
    const mie = (1 + cosGamma * cosGamma) / Math.pow(1 + H * H - 2 * H * cosGamma, 1.5);
    const f = (1 + A * Math.exp(B / (cosTheta + 0.01))) * (C + D * Math.exp(E * gamma) + F * cosGamma * cosGamma + G * mie + I * Math.sqrt(cosTheta));
    out[c] = f * sky.radiance[c]!;
  }
  return out;
}
