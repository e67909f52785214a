/**
 * Double-precision references of the BSDF lobe modules in src/materials/lobes (f without the
 * cosine, and the solid-angle pdf of the lobe's `sample`, non-delta parts only), written from the
 * papers in textbook form; the lobes of KHR extensions have theirs in their extension folders
 * (materials/extensions/<name>/reference.ts). The GPU tests compare the WGSL lobes against these.
 *
 * Convention (bsdf.wesl): local frame, wo.z > 0 (the caller orients the frame towards the viewer);
 * transmission lobes return wi with wi.z < 0. `eta` is the relative index of refraction n_t / n_i
 * across the surface, seen from wo's side.
 */
import { ggxDAniso, ggxG2, ggxVisibleNormalPdf, type Alphas } from './microfacet.ts';
import { dot, normalize, type Vec3 } from './vector.ts';

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

/** No scattering (the lobe's zero). */
export const none: LobeValue = { f: 0, pdf: 0 };

/** GGX reflection without Fresnel, D V (glTF Appendix B specular_brdf), VNDF-sampled; anisotropic. */
export function ggxReflection(alphas: Alphas, wo: Vec3, wi: Vec3): LobeValue {
  const a = lobeAlphas(alphas);
  if (wo[2] <= 0 || wi[2] <= 0 || isSmooth(a)) return none;
  const h = normalize([wo[0] + wi[0], wo[1] + wi[1], wo[2] + wi[2]]);
  const f = (ggxDAniso(h, a) * ggxG2(wo, wi, a)) / (4 * wo[2] * wi[2]);
  return { f, pdf: ggxVisibleNormalPdf(wo, h, a) / (4 * dot(wo, h)) };
}
