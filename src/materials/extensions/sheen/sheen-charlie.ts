/**
 * The KHR_materials_sheen BRDF in double precision (the CPU reference of sheen-charlie.wesl):
 * the "Charlie" distribution and visibility of Conty Estevez and Kulla 2017, "Production Friendly
 * Microfacet Sheen BRDF", in the forms of the KHR_materials_sheen implementation notes, with the
 * Khronos sample viewer's alpha = sheenRoughness^2. Kept apart from the layer's reference
 * (reference.ts) because the albedo tables the renderer builds read it.
 */
import { none, type LobeValue } from '../../reference/lobes.ts';
import { normalize, type Vec3 } from '../../reference/vector.ts';

/** Sheen roughness below this is raised to it: the distribution's exponent 1 / alpha stays finite. */
export const sheenMinRoughness = 0.01;

export function sheenAlpha(sheenRoughness: number): number {
  const r = Math.max(sheenRoughness, sheenMinRoughness);
  return r * r;
}

/** D(h) = (2 + 1 / alpha) sin(theta_h)^(1 / alpha) / (2 pi). */
export function charlieD(cosH: number, alpha: number): number {
  const sin2 = Math.max(0, 1 - cosH * cosH);
  const inv = 1 / alpha;
  return ((2 + inv) * Math.pow(sin2, 0.5 * inv)) / (2 * Math.PI);
}

function charlieL(x: number, alpha: number): number {
  const t = (1 - alpha) * (1 - alpha);
  const a = 21.5473 + (25.3245 - 21.5473) * t;
  const b = 3.82987 + (3.32435 - 3.82987) * t;
  const c = 0.19823 + (0.16801 - 0.19823) * t;
  const d = -1.9776 + (-1.27393 - -1.9776) * t;
  const e = -4.32054 + (-4.85967 - -4.32054) * t;
  return a / (1 + b * Math.pow(x, c)) + d * x + e;
}

/** The Charlie Lambda fit (KHR_materials_sheen, "Sheen visibility"). */
export function charlieLambda(cos: number, alpha: number): number {
  const c = Math.abs(cos);
  return c < 0.5 ? Math.exp(charlieL(c, alpha)) : Math.exp(2 * charlieL(0.5, alpha) - charlieL(1 - c, alpha));
}

/** f_sheen / sheenColor = D V with V = 1 / ((1 + Lambda(wo) + Lambda(wi)) 4 cos_o cos_i); reflection only. */
export function sheenBrdf(cosO: number, cosI: number, cosH: number, sheenRoughness: number): number {
  if (cosO <= 0 || cosI <= 0) return 0;
  const alpha = sheenAlpha(sheenRoughness);
  const v = 1 / ((1 + charlieLambda(cosO, alpha) + charlieLambda(cosI, alpha)) * 4 * cosO * cosI);
  return charlieD(cosH, alpha) * v;
}

/** Charlie sheen (KHR_materials_sheen), cosine-sampled. */
export function sheenCharlie(sheenRoughness: number, wo: Vec3, wi: Vec3): LobeValue {
  if (wo[2] <= 0 || wi[2] <= 0) return none;
  const h = normalize([wo[0] + wi[0], wo[1] + wi[1], wo[2] + wi[2]]);
  return { f: sheenBrdf(wo[2], wi[2], h[2], sheenRoughness), pdf: wi[2] / Math.PI };
}
