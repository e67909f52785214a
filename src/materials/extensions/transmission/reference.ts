/**
 * The CPU references of ggx-dielectric.wesl and ggx-thin-dielectric.wesl (KHR_materials_transmission),
 * double precision; conventions as in materials/reference/lobes.ts.
 */
import { fresnelDielectric } from '../../reference/fresnel.ts';
import { isSmooth, lobeAlphas, none, type LobeValue } from '../../reference/lobes.ts';
import { ggxDAniso, ggxG2, ggxVisibleNormalPdf, type Alphas } from '../../reference/microfacet.ts';
import { dot, mirrorZ, normalize, type Vec3 } from '../../reference/vector.ts';

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
