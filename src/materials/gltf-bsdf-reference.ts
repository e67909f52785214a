/**
 * Independent double-precision reference of the glTF 2.0 metallic-roughness BRDF, written straight
 * from the glTF 2.0 specification, Appendix B "BRDF Implementation" (in the textbook forms, not the
 * f32-stable rearrangements of the WGSL), plus the sampling pdf of `bsdf_sample` in
 * src/shaders/wgsl/bsdf-gltf.wgsl. Tests use it to check the shader; it is not used for rendering.
 *
 * Directions are unit vectors in the local shading frame (z = shading normal); wo points towards
 * the viewer, wi towards the light.
 */

import { luminance } from '../lighting/emissive-lights.ts';

export type Vec3 = readonly [number, number, number];

export interface GltfBsdfMaterial {
  /** Linear RGB in [0, 1]. */
  baseColor: Vec3;
  metallic: number;
  /** Perceptual roughness; alpha = roughness^2. */
  roughness: number;
  /** KHR_materials_ior (default 1.5). */
  ior: number;
}

/** Below this alpha the specular lobe is a delta (pbrt-v4 EffectivelySmooth); must match GLTF_DELTA_ALPHA. */
export const gltfDeltaAlpha = 1e-3;

function dot(a: Vec3, b: Vec3): number {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

function normalize(a: Vec3): Vec3 {
  const l = Math.hypot(a[0], a[1], a[2]);
  return [a[0] / l, a[1] / l, a[2] / l];
}

/**
 * Unpolarised Fresnel reflectance of a smooth dielectric (pbrt-v4 FrDielectric): cosThetaI on the
 * incident side (negative: from inside, eta inverted), eta = n_t / n_i.
 */
export function fresnelDielectric(cosThetaI: number, eta: number): number {
  // An index-matched interface reflects nothing (the limit of the formulas below, without rounding noise).
  if (eta === 1) return 0;
  let cosI = Math.min(1, Math.max(-1, cosThetaI));
  let e = eta;
  if (cosI < 0) {
    e = 1 / e;
    cosI = -cosI;
  }
  const sin2T = (1 - cosI * cosI) / (e * e);
  if (sin2T >= 1) return 1;
  const cosT = Math.sqrt(1 - sin2T);
  const rParl = (e * cosI - cosT) / (e * cosI + cosT);
  const rPerp = (cosI - e * cosT) / (cosI + e * cosT);
  return 0.5 * (rParl * rParl + rPerp * rPerp);
}

/** Appendix B: D = alpha^2 chi+(NdotH) / (pi ((NdotH)^2 (alpha^2 - 1) + 1)^2). */
export function ggxD(nDotH: number, alpha: number): number {
  if (nDotH <= 0) return 0;
  const a2 = alpha * alpha;
  const t = nDotH * nDotH * (a2 - 1) + 1;
  return a2 / (Math.PI * t * t);
}

/** Smith G1 for GGX (Heitz 2014): 2 NdotV / (NdotV + sqrt(alpha^2 + (1 - alpha^2) NdotV^2)). */
export function smithG1(nDotV: number, alpha: number): number {
  if (nDotV <= 0) return 0;
  const a2 = alpha * alpha;
  return (2 * nDotV) / (nDotV + Math.sqrt(a2 + (1 - a2) * nDotV * nDotV));
}

/** Appendix B height-correlated visibility V = G2 / (4 |NdotL| |NdotV|). */
export function smithHeightCorrelatedV(nDotL: number, nDotV: number, alpha: number): number {
  const a2 = alpha * alpha;
  const gv = nDotL * Math.sqrt(nDotV * nDotV * (1 - a2) + a2);
  const gl = nDotV * Math.sqrt(nDotL * nDotL * (1 - a2) + a2);
  return gv + gl > 0 ? 0.5 / (gv + gl) : 0;
}

function schlick(f0: number, cos: number): number {
  return f0 + (1 - f0) * Math.pow(1 - Math.abs(cos), 5);
}

/** f(wo, wi) without the cosine, non-delta lobes only (a delta specular lobe contributes nothing here). */
export function gltfBsdfEval(m: GltfBsdfMaterial, wo: Vec3, wi: Vec3): [number, number, number] {
  if (wo[2] <= 0 || wi[2] <= 0) return [0, 0, 0];
  const alpha = m.roughness * m.roughness;
  const h = normalize([wo[0] + wi[0], wo[1] + wi[1], wo[2] + wi[2]]);
  const vDotH = dot(wo, h);
  const nDotL = wi[2];
  const nDotV = wo[2];
  const specularBrdf = alpha < gltfDeltaAlpha ? 0 : ggxD(h[2], alpha) * smithHeightCorrelatedV(nDotL, nDotV, alpha);
  const fDielectric = fresnelDielectric(vDotH, m.ior);
  const out: [number, number, number] = [0, 0, 0];
  for (let c = 0; c < 3; c++) {
    const base = m.baseColor[c];
    const diffuse = base / Math.PI;
    const dielectricBrdf = (1 - fDielectric) * diffuse + fDielectric * specularBrdf;
    const metalBrdf = specularBrdf * schlick(base, vDotH);
    out[c] = (1 - m.metallic) * dielectricBrdf + m.metallic * metalBrdf;
  }
  return out;
}

/** Probability that bsdf_sample picks the specular lobe at wo (Fresnel-weighted lobe reflectances). */
export function gltfSpecularProbability(m: GltfBsdfMaterial, cosO: number): number {
  const f = fresnelDielectric(cosO, m.ior);
  const spec = (1 - m.metallic) * f + m.metallic;
  const diff = (1 - m.metallic) * (1 - f) * luminance(m.baseColor);
  return spec + diff > 0 ? spec / (spec + diff) : 0;
}

/** Solid-angle pdf of bsdf_sample's non-delta lobes: p_spec G1(wo) D(H) / (4 wo.z) + (1 - p_spec) cos / pi. */
export function gltfBsdfPdf(m: GltfBsdfMaterial, wo: Vec3, wi: Vec3): number {
  if (wo[2] <= 0 || wi[2] <= 0) return 0;
  const alpha = m.roughness * m.roughness;
  const pSpec = gltfSpecularProbability(m, wo[2]);
  let pdf = ((1 - pSpec) * wi[2]) / Math.PI;
  if (alpha >= gltfDeltaAlpha) {
    const h = normalize([wo[0] + wi[0], wo[1] + wi[1], wo[2] + wi[2]]);
    pdf += (pSpec * smithG1(wo[2], alpha) * ggxD(h[2], alpha)) / (4 * wo[2]);
  }
  return pdf;
}
