import { defineStructLayout, type StructLayout } from '../gpu-layout/struct-layout.ts';
import { add, dot, orthonormalBasis, scale, sub, type Vec3 } from './vec3.ts';

/**
 * The sun as a disc light of finite angular size, separate from the baked sky map, sampled by
 * uniform cone sampling and MIS-combined with the sky (its pdf is what BSDF-sampled rays hitting
 * the disc use). Radiance is uniform, or limb-darkened by Eddington's grey-atmosphere law
 * I(mu) / I(1) = (2 + 3 mu) / 5 (mu = cos of the angle on the solar surface), normalised so that the
 * disc's mean radiance, and so its irradiance, is unchanged.
 *
 * Cone parametrisation: 1 - cos(theta) = u1 (1 - cos(theta_max)), with 1 - cos(theta_max) stored
 * precomputed (2.7e-5 for the 0.53 degree sun: f32 cos(theta) itself cannot hold it). Whether a
 * direction d hits the disc is |d - sunDirection|^2 / 2 <= 1 - cos(theta_max) (exact, no
 * cancellation). Below the horizon (d.y < 0) the ground hides the sun: radiance 0, pdf unchanged.
 *
 * GPU uniform `SunLight` (32 bytes): direction, oneMinusCosThetaMax, radiance, limbDarkening.
 */
export interface SunLight {
  /** Unit direction towards the sun's centre. */
  direction: Vec3;
  /** 1 - cos of the angular radius. */
  oneMinusCosThetaMax: number;
  /** Mean radiance over the disc (linear RGB). */
  radiance: Vec3;
  limbDarkening: boolean;
}

export const sunLightLayout: StructLayout = defineStructLayout('SunLight', 1, [
  ['direction', 'vec3f', 'unit, towards the sun'],
  ['oneMinusCosThetaMax', 'f32', '1 - cos(angular radius)'],
  ['radiance', 'vec3f', 'mean radiance over the disc'],
  ['limbDarkening', 'u32', '1: Eddington limb darkening'],
]);

/** 1 - cos(x) without cancellation: 2 sin^2(x / 2). */
export function oneMinusCos(x: number): number {
  const s = Math.sin(x / 2);
  return 2 * s * s;
}

/** Solid angle of the disc: 2 pi (1 - cos theta_max). */
export function sunSolidAngle(sun: SunLight): number {
  return 2 * Math.PI * sun.oneMinusCosThetaMax;
}

/** Radiance relative to the mean at fraction s = (1 - cos alpha) / (1 - cos theta_max) of the disc. */
function limbFactor(sun: SunLight, s: number): number {
  if (!sun.limbDarkening) return 1;
  // Mean of mu = sqrt(1 - s) over s uniform in [0, 1] is 2/3, so the mean of (2 + 3 mu) / 4 is 1.
  return (2 + 3 * Math.sqrt(Math.max(0, 1 - s))) / 4;
}

/** Radiance arriving from unit direction `d` (0 outside the disc or below the horizon). */
export function sunRadiance(sun: SunLight, d: readonly number[]): Vec3 {
  if (d[1]! < 0) return [0, 0, 0];
  const diff = sub(d, sun.direction);
  const omc = dot(diff, diff) / 2;
  if (omc > sun.oneMinusCosThetaMax) return [0, 0, 0];
  return scale(sun.radiance, limbFactor(sun, omc / sun.oneMinusCosThetaMax));
}

export interface SunSample {
  direction: Vec3;
  pdf: number;
  radiance: Vec3;
}

/** Uniform direction in the sun's cone. */
export function sampleSun(sun: SunLight, u1: number, u2: number): SunSample {
  const omc = u1 * sun.oneMinusCosThetaMax;
  const cosTheta = 1 - omc;
  const sinTheta = Math.sqrt(Math.max(0, omc * (2 - omc)));
  const phi = 2 * Math.PI * u2;
  const { t, b } = orthonormalBasis(sun.direction);
  const direction = add(add(scale(t, sinTheta * Math.cos(phi)), scale(b, sinTheta * Math.sin(phi))), scale(sun.direction, cosTheta));
  const radiance = direction[1] < 0 ? ([0, 0, 0] as Vec3) : scale(sun.radiance, limbFactor(sun, u1));
  return { direction, pdf: 1 / sunSolidAngle(sun), radiance };
}

/** Solid-angle density of `sampleSun` at unit `d`. */
export function sunPdf(sun: SunLight, d: readonly number[]): number {
  const diff = sub(d, sun.direction);
  return dot(diff, diff) / 2 <= sun.oneMinusCosThetaMax ? 1 / sunSolidAngle(sun) : 0;
}
