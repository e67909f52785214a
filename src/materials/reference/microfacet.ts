/**
 * Anisotropic GGX / Trowbridge-Reitz microfacet functions in double precision (the CPU reference of
 * microfacet.wesl), in the local frame (z = normal, x = the anisotropy direction), written in the
 * textbook forms: D (Walter et al. 2007; Burley 2012 for the anisotropic form), Smith Lambda and the
 * height-correlated G2 (Heitz 2014), the distribution of visible normals and its sampling
 * (Heitz 2018), reflection and refraction through a microfacet normal (pbrt-v4 Reflect / Refract).
 */
import { dot, normalize, type Vec3 } from './vector.ts';

export interface Alphas {
  readonly x: number;
  readonly y: number;
}

/** D(h) = 1 / (pi ax ay ((hx / ax)^2 + (hy / ay)^2 + hz^2)^2), 0 below the surface. */
export function ggxDAniso(h: Vec3, a: Alphas): number {
  if (h[2] <= 0) return 0;
  const t = (h[0] / a.x) ** 2 + (h[1] / a.y) ** 2 + h[2] ** 2;
  return 1 / (Math.PI * a.x * a.y * t * t);
}

/** Smith Lambda(w) = (-1 + sqrt(1 + (ax^2 wx^2 + ay^2 wy^2) / wz^2)) / 2 (Heitz 2014 eq. 86, anisotropic). */
export function ggxLambda(w: Vec3, a: Alphas): number {
  const tan2 = ((a.x * w[0]) ** 2 + (a.y * w[1]) ** 2) / (w[2] * w[2]);
  return (-1 + Math.sqrt(1 + tan2)) / 2;
}

export function ggxG1Aniso(w: Vec3, a: Alphas): number {
  return 1 / (1 + ggxLambda(w, a));
}

/** Height-correlated masking-shadowing G2 = 1 / (1 + Lambda(wo) + Lambda(wi)) (Heitz 2014 eq. 99). */
export function ggxG2(wo: Vec3, wi: Vec3, a: Alphas): number {
  return 1 / (1 + ggxLambda(wo, a) + ggxLambda(wi, a));
}

/** Visible-normal density D_wo(h) = G1(wo) max(0, wo.h) D(h) / wo.z (Heitz 2018 eq. 3), wo.z > 0. */
export function ggxVisibleNormalPdf(wo: Vec3, h: Vec3, a: Alphas): number {
  return (ggxG1Aniso(wo, a) * Math.max(0, dot(wo, h)) * ggxDAniso(h, a)) / wo[2];
}

/**
 * Samples h ~ D_wo with the spherical-cap method (Dupuy and Benyoub 2023), the same mapping as
 * sample_ggx_vndf in microfacet.wesl. wo.z > 0.
 */
export function sampleGgxVisibleNormal(wo: Vec3, a: Alphas, u0: number, u1: number): Vec3 {
  const ws = normalize([wo[0] * a.x, wo[1] * a.y, wo[2]]);
  const phi = 2 * Math.PI * u0;
  const z = (1 - u1) * (1 + ws[2]) - ws[2];
  const s = Math.sqrt(Math.max(0, 1 - z * z));
  const hs: Vec3 = [s * Math.cos(phi) + ws[0], s * Math.sin(phi) + ws[1], z + ws[2]];
  return normalize([hs[0] * a.x, hs[1] * a.y, Math.max(hs[2], 0)]);
}

/**
 * The inverse of sampleGgxVisibleNormal: the point (u0, u1) of the unit square that samples the
 * visible normal h. In the stretched configuration h_std = c + wo_std with c on the unit sphere, so
 * c is wo_std reflected about h_std's direction.
 */
export function ggxVisibleNormalSamplePoint(wo: Vec3, a: Alphas, h: Vec3): [number, number] {
  const ws = normalize([wo[0] * a.x, wo[1] * a.y, wo[2]]);
  const n = normalize([h[0] / a.x, h[1] / a.y, h[2]]);
  const k = 2 * dot(n, ws);
  const c: Vec3 = [k * n[0] - ws[0], k * n[1] - ws[1], k * n[2] - ws[2]];
  let u0 = Math.atan2(c[1], c[0]) / (2 * Math.PI);
  if (u0 < 0) u0 += 1;
  return [u0, Math.min(1, Math.max(0, 1 - (c[2] + ws[2]) / (1 + ws[2])))];
}

/** Mirror reflection of wo about the unit normal n. */
export function reflect(wo: Vec3, n: Vec3): Vec3 {
  const c = 2 * dot(wo, n);
  return [c * n[0] - wo[0], c * n[1] - wo[1], c * n[2] - wo[2]];
}

/**
 * Refraction of wo through a surface with normal n and relative index eta = n_t / n_i for wo on
 * n's side (pbrt-v4 Refract); null under total internal reflection.
 */
export function refract(wo: Vec3, n: Vec3, eta: number): Vec3 | null {
  let cosI = dot(n, wo);
  let e = eta;
  let nn = n;
  if (cosI < 0) {
    e = 1 / e;
    cosI = -cosI;
    nn = [-n[0], -n[1], -n[2]];
  }
  const sin2T = Math.max(0, 1 - cosI * cosI) / (e * e);
  if (sin2T >= 1) return null;
  const cosT = Math.sqrt(1 - sin2T);
  return [-wo[0] / e + (cosI / e - cosT) * nn[0], -wo[1] / e + (cosI / e - cosT) * nn[1], -wo[2] / e + (cosI / e - cosT) * nn[2]];
}

/** KHR_materials_anisotropy: the alpha along the anisotropy direction, mix(alpha, 1, strength^2). */
export function anisotropicAlphas(roughness: number, anisotropy: number): Alphas {
  const alpha = roughness * roughness;
  return { x: alpha + (1 - alpha) * anisotropy * anisotropy, y: alpha };
}
