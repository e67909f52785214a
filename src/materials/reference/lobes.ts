/**
 * Double-precision references of every BSDF lobe module in src/materials/lobes (f without the
 * cosine, and the solid-angle pdf of the lobe's `sample`, non-delta parts only), written from the
 * papers in textbook form. The GPU tests compare the WGSL lobes against these.
 *
 * Convention (bsdf.wesl): local frame, wo.z > 0 (the caller orients the frame towards the viewer);
 * transmission lobes return wi with wi.z < 0. `eta` is the relative index of refraction n_t / n_i
 * across the surface, seen from wo's side.
 */
import { fresnelDielectric } from './fresnel.ts';
import { ggxDAniso, ggxG2, ggxVisibleNormalPdf, type Alphas } from './microfacet.ts';
import { sheenBrdf } from './sheen.ts';
import { dot, mirrorZ, normalize, type Vec3 } from './vector.ts';

/** Below this alpha (on both axes) a GGX lobe is a delta (pbrt-v4 EffectivelySmooth); GLTF_DELTA_ALPHA in WGSL. */
export const deltaAlpha = 1e-3;

export const isSmooth = (a: Alphas): boolean => Math.max(a.x, a.y) < deltaAlpha;

/** The least alpha of a lobe that is not smooth, on either axis (pbrt-v4 TrowbridgeReitzDistribution); GGX_MIN_ALPHA in WGSL. */
export const minAlpha = 1e-4;

/** The alphas a lobe works with: unchanged when smooth, else each at least minAlpha (ggx-reflection.wesl lobe_alphas). */
export function lobeAlphas(a: Alphas): Alphas {
  return isSmooth(a) ? a : { x: Math.max(a.x, minAlpha), y: Math.max(a.y, minAlpha) };
}

export interface LobeValue {
  f: number;
  pdf: number;
}

const none: LobeValue = { f: 0, pdf: 0 };

/** Lambertian transmission: f = 1 / pi (times its colour) for wi below, cosine-sampled there. */
export function lambertTransmission(wo: Vec3, wi: Vec3): LobeValue {
  if (wo[2] <= 0 || wi[2] >= 0) return none;
  return { f: 1 / Math.PI, pdf: -wi[2] / Math.PI };
}

/** GGX reflection without Fresnel, D V (glTF Appendix B specular_brdf), VNDF-sampled; anisotropic. */
export function ggxReflection(alphas: Alphas, wo: Vec3, wi: Vec3): LobeValue {
  const a = lobeAlphas(alphas);
  if (wo[2] <= 0 || wi[2] <= 0 || isSmooth(a)) return none;
  const h = normalize([wo[0] + wi[0], wo[1] + wi[1], wo[2] + wi[2]]);
  const f = (ggxDAniso(h, a) * ggxG2(wo, wi, a)) / (4 * wo[2] * wi[2]);
  return { f, pdf: ggxVisibleNormalPdf(wo, h, a) / (4 * dot(wo, h)) };
}

/**
 * The half vector of a refraction pair (Walter et al. 2007 eq. 16): normalize(eta wi + wo), turned
 * to the upper hemisphere; null when degenerate.
 */
function refractionHalfVector(wo: Vec3, wi: Vec3, eta: number): Vec3 | null {
  const m: Vec3 = [eta * wi[0] + wo[0], eta * wi[1] + wo[1], eta * wi[2] + wo[2]];
  const l = Math.hypot(m[0], m[1], m[2]);
  if (!(l > 0)) return null;
  const h = normalize(m);
  return h[2] < 0 ? [-h[0], -h[1], -h[2]] : h;
}

/**
 * Rough dielectric interface, reflection + refraction (Walter et al. 2007, "Microfacet Models for
 * Refraction through Rough Surfaces"; pbrt-v4 DielectricBxDF with height-correlated G2 and the
 * radiance scaling 1 / eta^2 of transmitted radiance, section 9.5.2). The microfacet normal is
 * VNDF-sampled, then reflection or refraction is chosen with probability F(wo.h).
 */
export function ggxDielectric(alphas: Alphas, eta: number, wo: Vec3, wi: Vec3): LobeValue {
  const a = lobeAlphas(alphas);
  if (wo[2] <= 0 || wi[2] === 0 || isSmooth(a) || eta === 1) return none;
  const reflect = wi[2] > 0;
  const etap = reflect ? 1 : eta;
  const h = refractionHalfVector(wo, wi, etap);
  if (!h) return none;
  // Discard back-facing microfacets.
  if (dot(h, wi) * wi[2] < 0 || dot(h, wo) * wo[2] < 0) return none;
  const r = fresnelDielectric(dot(wo, h), eta);
  const d = ggxDAniso(h, a);
  const g = ggxG2(wo, wi, a);
  const vndf = ggxVisibleNormalPdf(wo, h, a);
  if (reflect) return { f: (d * g * r) / Math.abs(4 * wi[2] * wo[2]), pdf: (vndf / (4 * Math.abs(dot(wo, h)))) * r };
  const denom = (dot(wi, h) + dot(wo, h) / etap) ** 2;
  const f = (d * (1 - r) * g * Math.abs((dot(wi, h) * dot(wo, h)) / (denom * wi[2] * wo[2]))) / (etap * etap);
  return { f, pdf: ((vndf * Math.abs(dot(wi, h))) / denom) * (1 - r) };
}

/**
 * Thin-walled rough dielectric (KHR_materials_transmission, "Transmission BTDF"): reflection F D V,
 * and transmission through a sheet too thin to displace the ray, (1 - F) D V evaluated at the
 * mirror image of wi through the surface (the half vector H_T of the extension's notes). One VNDF
 * sample serves both; reflection is chosen with probability F(wo.h).
 */
export function ggxThinDielectric(alphas: Alphas, eta: number, wo: Vec3, wi: Vec3): LobeValue {
  const a = lobeAlphas(alphas);
  if (wo[2] <= 0 || wi[2] === 0 || isSmooth(a)) return none;
  const reflect = wi[2] > 0;
  const w = reflect ? wi : mirrorZ(wi);
  const h = normalize([wo[0] + w[0], wo[1] + w[1], wo[2] + w[2]]);
  const r = fresnelDielectric(dot(wo, h), eta);
  const weight = reflect ? r : 1 - r;
  const f = (ggxDAniso(h, a) * ggxG2(wo, w, a)) / (4 * wo[2] * w[2]);
  return { f: weight * f, pdf: weight * (ggxVisibleNormalPdf(wo, h, a) / (4 * dot(wo, h))) };
}

/** Charlie sheen (KHR_materials_sheen), cosine-sampled. */
export function sheenCharlie(sheenRoughness: number, wo: Vec3, wi: Vec3): LobeValue {
  if (wo[2] <= 0 || wi[2] <= 0) return none;
  const h = normalize([wo[0] + wi[0], wo[1] + wi[1], wo[2] + wi[2]]);
  return { f: sheenBrdf(wo[2], wi[2], h[2], sheenRoughness), pdf: wi[2] / Math.PI };
}
