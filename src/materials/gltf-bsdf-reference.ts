/**
 * Independent double-precision reference of the glTF BSDF of gltf-bsdf.wesl. The metallic-roughness
 * core is written straight from the glTF 2.0 specification, Appendix B "BRDF Implementation" (in
 * the textbook forms, not the f32-stable rearrangements of the WGSL); the KHR extensions follow
 * each specification and the layering the WGSL module documents, with the albedo tables read
 * through the same interpolation (table-lookup.ts). Also the sampling pdf of its `sample`. Tests
 * use it to check the shader; it is not used for rendering.
 *
 * Directions are unit vectors in the local shading frame (z = shading normal, x = the anisotropy
 * direction); wo points towards the viewer (wo.z > 0), wi towards the light.
 */

import {
  MATERIAL_FLAG_ANISOTROPY,
  MATERIAL_FLAG_DIFFUSE_TRANSMISSION,
  MATERIAL_FLAG_ENERGY_COMPENSATION,
  MATERIAL_FLAG_IOR_INFINITE,
  MATERIAL_FLAG_IRIDESCENCE,
  MATERIAL_FLAG_SPECULAR,
  MATERIAL_FLAG_TRANSMISSION,
  MATERIAL_FLAG_VOLUME,
} from '../gpu-layout/constants.ts';
import { luminance } from '../lighting/emissive-lights.ts';
import { dielectricEtaCoordinate, lookupDielectricAlbedo, lookupDielectricAlbedoAverage, lookupDielectricInterfaceAlbedo, lookupGgxAlbedo } from './energy/table-lookup.ts';
import { iridescentFresnel } from './extensions/iridescence/reference.ts';
import { dielectricFresnelRgb, fresnelDielectric, fresnelSchlick, iorToF0 } from './reference/fresnel.ts';
import { anisotropicAlphas, ggxDAniso, ggxG2, ggxVisibleNormalPdf, ggxVisibleNormalSamplePoint, sampleGgxVisibleNormal, type Alphas } from './reference/microfacet.ts';
import { lobeAlphas } from './reference/lobes.ts';
import type { LayerParams, MaterialLayerReference } from './material-layer.ts';
import { materialLayerReferences } from './material-layers.generated.ts';
import { maxComponent } from './reference/vector.ts';

export { fresnelDielectric };

export type Vec3 = readonly [number, number, number];

/** The parameters of the KHR extension layers over the base (material-layers.generated.ts), by registry key. */
export type GltfBsdfLayers = { [L in (typeof materialLayerReferences)[number] as L['key']]?: LayerParams<L> };

/**
 * A glTF material as the BSDF sees it; the optional fields are the KHR extensions (absent: not
 * used), the layers among them (clearcoat, sheen) under their registry keys.
 */
export type GltfBsdfMaterial = GltfBsdfBase & GltfBsdfLayers;

/** The base of the glTF BSDF: metallic-roughness and the KHR extensions that change it. */
export interface GltfBsdfBase {
  /** Linear RGB in [0, 1]. */
  baseColor: Vec3;
  metallic: number;
  /** Perceptual roughness; alpha = roughness^2. */
  roughness: number;
  /**
   * KHR_materials_ior (default 1.5); with extensions, the relative index n_t / n_i across the
   * surface seen from wo's side. Infinity: KHR_materials_ior's ior = 0 mode (Fresnel = 1).
   */
  ior: number;
  /** KHR_materials_specular. */
  specular?: { factor: number; color: Vec3 };
  /** KHR_materials_transmission; `refractive` with KHR_materials_volume, else thin-walled. */
  transmission?: { factor: number; refractive: boolean };
  /** KHR_materials_diffuse_transmission. */
  diffuseTransmission?: { factor: number; color: Vec3 };
  /** KHR_materials_iridescence (thickness in nm). */
  iridescence?: { factor: number; thickness: number; ior: number };
  /** KHR_materials_anisotropy strength along the local x axis. */
  anisotropy?: number;
  /** Multiple-scattering energy compensation. */
  energyCompensation?: boolean;
}

/** The MATERIAL_FLAG_* bits the GPU BSDF's Params.ext holds for a material. */
export function gltfBsdfExtensionFlags(m: GltfBsdfMaterial): number {
  let f = 0;
  if (m.specular) f |= MATERIAL_FLAG_SPECULAR;
  if (m.transmission) f |= MATERIAL_FLAG_TRANSMISSION | (m.transmission.refractive ? MATERIAL_FLAG_VOLUME : 0);
  if (m.diffuseTransmission) f |= MATERIAL_FLAG_DIFFUSE_TRANSMISSION;
  for (const layer of layersOf(m)) f |= layer.reference.flag;
  if (m.iridescence) f |= MATERIAL_FLAG_IRIDESCENCE;
  if (m.anisotropy !== undefined) f |= MATERIAL_FLAG_ANISOTROPY;
  if (m.energyCompensation) f |= MATERIAL_FLAG_ENERGY_COMPENSATION;
  if (!Number.isFinite(m.ior)) f |= MATERIAL_FLAG_IOR_INFINITE;
  return f;
}

/** Every layer reference, loosely typed, for code that handles them all alike. */
const anyLayerReferences = materialLayerReferences as unknown as readonly MaterialLayerReference<string, never>[];

/** A layer's parameters in a material (undefined: the material does not have it). */
function layerParams(m: GltfBsdfMaterial, reference: MaterialLayerReference<string, never>): never | undefined {
  return (m as unknown as Readonly<Record<string, never | undefined>>)[reference.key];
}

/** The layers a material has, outermost first, with their parameters. */
function layersOf(m: GltfBsdfMaterial): { reference: MaterialLayerReference<string, never>; params: never }[] {
  return anyLayerReferences.flatMap((reference) => {
    const params = layerParams(m, reference);
    return params === undefined ? [] : [{ reference, params }];
  });
}

/** Floats of each layer in PackedLobeParams.layers (two vec4s). */
const packedLayerFloats = 8;

/** The GPU BSDF's PackedLobeParams for a material (gltf-bsdf.wesl unpack_params), layers included. */
export function packGltfBsdfParams(m: GltfBsdfMaterial): number[] {
  const ext = gltfBsdfExtensionFlags(m);
  const base = [
    ...m.baseColor, m.metallic,
    m.roughness, Number.isFinite(m.ior) ? m.ior : 0, ext, m.anisotropy ?? 0,
    ...(m.specular?.color ?? [1, 1, 1]), m.specular?.factor ?? 1,
    ...(m.diffuseTransmission?.color ?? [1, 1, 1]), m.diffuseTransmission?.factor ?? 0,
    m.transmission?.factor ?? 0, m.iridescence?.factor ?? 0, m.iridescence?.thickness ?? 0, m.iridescence?.ior ?? 1.3,
    ...new Array<number>(12).fill(0),
  ];
  const layers = anyLayerReferences.flatMap((reference) => {
    const params = layerParams(m, reference);
    const packed = params === undefined ? [] : reference.pack(params);
    if (packed.length > packedLayerFloats) throw new Error(`layer ${reference.key} packs ${packed.length} floats, more than ${packedLayerFloats}`);
    return [...packed, ...new Array<number>(packedLayerFloats - packed.length).fill(0)];
  });
  return [...base, ...layers];
}

/** Whether a material uses any extension (the plain core otherwise). */
function extended(m: GltfBsdfMaterial): boolean {
  return gltfBsdfExtensionFlags(m) !== 0;
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
  if (extended(m)) return [...extendedEval(m, wo, wi).f] as [number, number, number];
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
  if (extended(m)) return extendedEval(m, wo, wi).pdf;
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

// ---- The KHR extensions (mirrors gltf-bsdf.wesl) -------------------------------------------------

const add3 = (a: Vec3, b: Vec3): Vec3 => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
const mul3 = (a: Vec3, b: Vec3): Vec3 => [a[0] * b[0], a[1] * b[1], a[2] * b[2]];
const scale3 = (a: Vec3, k: number): Vec3 => [a[0] * k, a[1] * k, a[2] * k];
const mix3 = (a: Vec3, b: Vec3, t: number): Vec3 => [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t, a[2] + (b[2] - a[2]) * t];

function alphasOf(m: GltfBsdfMaterial): Alphas {
  if (m.anisotropy !== undefined) return lobeAlphas(anisotropicAlphas(m.roughness, m.anisotropy));
  const a = m.roughness * m.roughness;
  return { x: a, y: a };
}

const smoothAlphas = (a: Alphas): boolean => Math.max(a.x, a.y) < gltfDeltaAlpha;

function plainDielectricFresnel(m: GltfBsdfMaterial, cos: number): Vec3 {
  if (m.specular || !Number.isFinite(m.ior)) {
    return dielectricFresnelRgb(cos, { eta: m.ior, specular: m.specular?.factor ?? 1, specularColor: m.specular?.color ?? [1, 1, 1] });
  }
  const f = fresnelDielectric(cos, m.ior);
  return [f, f, f];
}

/** The dielectric Fresnel term at cos = wo.h: KHR_materials_specular, then the thin film mixed in. */
export function gltfDielectricFresnel(m: GltfBsdfMaterial, cos: number): Vec3 {
  const f = plainDielectricFresnel(m, cos);
  if (!m.iridescence) return f;
  const specular = m.specular?.factor ?? 1;
  const color = m.specular?.color ?? [1, 1, 1];
  const f0Ior = Number.isFinite(m.ior) ? iorToF0(m.ior) : 1;
  const baseF0: Vec3 = [0, 1, 2].map((c) => Math.min(f0Ior * color[c]!, 1) * specular) as unknown as Vec3;
  return mix3(f, iridescentFresnel(1, m.iridescence.ior, baseF0, m.iridescence.thickness, cos), m.iridescence.factor);
}

function metalFresnel(m: GltfBsdfMaterial, cos: number): Vec3 {
  const f = fresnelSchlick(m.baseColor, cos);
  if (!m.iridescence) return f;
  return mix3(f, iridescentFresnel(1, m.iridescence.ior, m.baseColor, m.iridescence.thickness, cos), m.iridescence.factor);
}

function dielectricSpecularAlbedo(m: GltfBsdfMaterial, cos: number): { value: number; average: number } {
  const r = m.roughness;
  const y = dielectricEtaCoordinate(m.ior);
  const eF = lookupDielectricAlbedo(cos, r, y);
  const avgF = lookupDielectricAlbedoAverage(r, y);
  if (!m.specular && Number.isFinite(m.ior)) return { value: eF, average: avgF };
  const e1 = lookupGgxAlbedo(cos, r);
  const avg1 = lookupDielectricAlbedoAverage(r, 1);
  const f0Ior = Number.isFinite(m.ior) ? iorToF0(m.ior) : 1;
  const spec = m.specular?.factor ?? 1;
  const color = m.specular?.color ?? [1, 1, 1];
  const f0Max = Math.max(...[0, 1, 2].map((c) => Math.min(f0Ior * color[c]!, 1) * spec));
  const shaped = f0Ior >= 1 ? e1 : (eF - f0Ior * e1) / (1 - f0Ior);
  const shapedAvg = f0Ior >= 1 ? avg1 : (avgF - f0Ior * avg1) / (1 - f0Ior);
  return { value: f0Max * e1 + (spec - f0Max) * shaped, average: f0Max * avg1 + (spec - f0Max) * shapedAvg };
}

function diffuseWeight(m: GltfBsdfMaterial, cosO: number, cosI: number, fH: number): number {
  if (m.energyCompensation) {
    const eo = dielectricSpecularAlbedo(m, cosO);
    const ei = dielectricSpecularAlbedo(m, Math.abs(cosI));
    if (eo.average >= 1) return 0;
    return Math.max(0, ((1 - eo.value) * (1 - ei.value)) / (1 - eo.average));
  }
  return 1 - fH;
}

function metalCompensation(m: GltfBsdfMaterial, cosO: number): Vec3 {
  if (!m.energyCompensation) return [1, 1, 1];
  const e = lookupGgxAlbedo(cosO, m.roughness);
  return [0, 1, 2].map((c) => 1 + (m.baseColor[c]! * (1 - e)) / e) as unknown as Vec3;
}

function transmissionCompensation(m: GltfBsdfMaterial, cosO: number): number {
  if (!m.energyCompensation || indexMatched(m)) return 1;
  const e = m.transmission?.refractive ? lookupDielectricInterfaceAlbedo(cosO, m.roughness, dielectricEtaCoordinate(m.ior)) : lookupGgxAlbedo(cosO, m.roughness);
  return 1 / e;
}

/**
 * A refractive interface of relative index exactly 1 (gltf-bsdf.wesl index_matched): its
 * transmission is the delta wi = -wo at every roughness (Walter et al. 2007's eta -> 1 limit).
 */
export function indexMatched(m: GltfBsdfMaterial): boolean {
  return m.transmission?.refractive === true && m.ior === 1;
}

/**
 * The thin wall's slope scale (gltf-bsdf.wesl thin_slope_scale): its prisms deflect by (eta - 1) A,
 * so the transmitted lobe's alphas are the specular lobe's times clamp(2 |eta - 1|, 0, 1).
 */
export function thinSlopeScale(m: GltfBsdfMaterial): number {
  if (!Number.isFinite(m.ior)) return 1;
  return Math.min(1, Math.max(0, 2 * Math.abs(m.ior - 1)));
}

function thinTransmissionAlphas(m: GltfBsdfMaterial): Alphas {
  const a = alphasOf(m);
  const k = thinSlopeScale(m);
  return lobeAlphas({ x: a.x * k, y: a.y * k });
}

/** Transmission straight through, a delta (gltf-bsdf.wesl straight_transmission). */
export function straightTransmission(m: GltfBsdfMaterial): boolean {
  if (!m.transmission) return false;
  return m.transmission.refractive ? indexMatched(m) : smoothAlphas(thinTransmissionAlphas(m));
}

/**
 * The delta transmission of a surface that transmits straight through (straightTransmission): its
 * weight (1 - metallic) transmission baseColor (1 - max F(wo.h)), the light each visible microfacet
 * does not reflect, averaged over the distribution of visible normals D_wo (Heitz 2018) by an
 * n x n midpoint rule in the sampling mapping's unit square (whose image measure is D_wo), or at
 * h = n when smooth. The layers above (clearcoat, sheen) are not included.
 */
export function gltfStraightTransmittance(m: GltfBsdfMaterial, wo: Vec3, n = 256): Vec3 {
  if (!straightTransmission(m) || wo[2] <= 0) return [0, 0, 0];
  const a = alphasOf(m);
  const k = (1 - m.metallic) * m.transmission!.factor;
  const at = (cos: number): number => 1 - maxComponent(gltfDielectricFresnel(m, cos));
  let mean = 0;
  if (smoothAlphas(a)) {
    mean = at(wo[2]);
  } else {
    for (let i = 0; i < n; i++) {
      for (let j = 0; j < n; j++) {
        const h = sampleGgxVisibleNormal(wo, a, (i + 0.5) / n, (j + 0.5) / n);
        mean += at(Math.min(1, Math.max(0, dot(wo, h))));
      }
    }
    mean /= n * n;
  }
  return scale3(m.baseColor, k * mean);
}

interface Weights {
  /** Per layer of the registry (0 where the material has none). */
  layers: number[];
  microfacet: number;
  diffuse: number;
  diffuseReflect: number;
}

/** Lobe selection probabilities at wo (gltf-bsdf.wesl lobe_weights). */
export function gltfLobeWeights(m: GltfBsdfMaterial, wo: Vec3): Weights {
  const f = maxComponent(gltfDielectricFresnel(m, wo[2]));
  const mt = m.metallic;
  const t = m.transmission?.factor ?? 0;
  const dt = m.diffuseTransmission?.factor ?? 0;
  const lum = luminance(m.baseColor);
  let microfacet = (1 - mt) * f + mt;
  let diffuse = (1 - mt) * (1 - f) * lum;
  let diffuseReflect = 1;
  if (m.transmission || m.diffuseTransmission) {
    microfacet += (1 - mt) * (1 - f) * t * lum;
    const dr = (1 - dt) * lum;
    const dtr = dt * luminance(m.diffuseTransmission?.color ?? [1, 1, 1]);
    diffuse = (1 - mt) * (1 - f) * (1 - t) * (dr + dtr);
    diffuseReflect = dr + dtr > 0 ? dr / (dr + dtr) : 1;
  }
  // The layers' reflectance estimates, each times what the layers above pass on.
  let below = 1;
  const layers = anyLayerReferences.map((reference) => {
    const params = layerParams(m, reference);
    if (params === undefined) return 0;
    const r = reference.reflectance(params, wo);
    const w = below * r;
    below *= 1 - r;
    return w;
  });
  microfacet *= below;
  diffuse *= below;
  const total = layers.reduce((a, b) => a + b, 0) + microfacet + diffuse;
  if (total <= 0) return { layers: layers.map(() => 0), microfacet: 0, diffuse: 1, diffuseReflect: 1 };
  return { layers: layers.map((w) => w / total), microfacet: microfacet / total, diffuse: diffuse / total, diffuseReflect };
}

/** Probability of reflection among the microfacet lobes given the dielectric F (largest channel, thin film included) at h. */
export function gltfReflectProbability(m: GltfBsdfMaterial, f: number): number {
  if (!m.transmission) return 1;
  const mt = m.metallic;
  const r = mt + (1 - mt) * f;
  const t = (1 - mt) * (1 - f) * m.transmission.factor * luminance(m.baseColor);
  return r + t > 0 ? r / (r + t) : 1;
}

function refractionHalfVector(wo: Vec3, wi: Vec3, eta: number): Vec3 | null {
  const v: Vec3 = [eta * wi[0] + wo[0], eta * wi[1] + wo[1], eta * wi[2] + wo[2]];
  const l = Math.hypot(v[0], v[1], v[2]);
  if (!(l > 0)) return null;
  const h = scale3(v, 1 / l);
  return h[2] < 0 ? scale3(h, -1) : h;
}

function baseEval(m: GltfBsdfMaterial, w: Weights, wo: Vec3, wi: Vec3): { f: Vec3; microfacetPdf: number; diffusePdf: number } {
  const a = alphasOf(m);
  const smooth = smoothAlphas(a);
  const mt = m.metallic;
  const t = m.transmission?.factor ?? 0;
  const dt = m.diffuseTransmission?.factor ?? 0;
  const upper = wi[2] > 0;
  let f: Vec3 = [0, 0, 0];
  let microfacetPdf = 0;
  let diffusePdf = 0;
  // One microfacet normal for the pair (gltf-bsdf.wesl base_eval).
  const wm: Vec3 = [wi[0], wi[1], Math.abs(wi[2])];
  let h = normalize(add3(wo, wm));
  let refracted = false;
  if (!upper && m.transmission?.refractive && t > 0 && !smooth && m.ior !== 1) {
    const hr = refractionHalfVector(wo, wi, m.ior);
    if (hr && hr[2] > 0 && dot(hr, wi) < 0 && dot(hr, wo) > 0) {
      h = hr;
      refracted = true;
    }
  }
  const cosH = Math.min(1, Math.max(0, dot(wo, h)));
  const fd = gltfDielectricFresnel(m, cosH);
  const fMax = maxComponent(fd);
  const weight = diffuseWeight(m, wo[2], wi[2], fMax);
  if (upper) {
    if (!smooth) {
      const spec = (ggxDAniso(h, a) * ggxG2(wo, wi, a)) / (4 * wo[2] * wi[2]);
      const metal = mul3(metalFresnel(m, cosH), metalCompensation(m, wo[2]));
      let dielectric = fd;
      if (m.energyCompensation && m.transmission) dielectric = scale3(dielectric, t * transmissionCompensation(m, wo[2]) + (1 - t));
      f = scale3(add3(scale3(metal, mt), scale3(dielectric, 1 - mt)), spec);
      microfacetPdf = (ggxVisibleNormalPdf(wo, h, a) / (4 * dot(wo, h))) * gltfReflectProbability(m, fMax);
    }
    f = add3(f, scale3(m.baseColor, ((1 - mt) * weight * (1 - t) * (1 - dt)) / Math.PI));
    diffusePdf = (w.diffuseReflect * wi[2]) / Math.PI;
    return { f, microfacetPdf, diffusePdf };
  }
  if (m.transmission && !smooth && t > 0) {
    const k = (1 - mt) * t * (1 - fMax) * transmissionCompensation(m, wo[2]);
    if (refracted) {
      const denom = (dot(wi, h) + cosH / m.ior) ** 2;
      const btdf = (ggxDAniso(h, a) * ggxG2(wo, wi, a) * Math.abs((dot(wi, h) * cosH) / (denom * wi[2] * wo[2]))) / (m.ior * m.ior);
      f = scale3(m.baseColor, k * btdf);
      microfacetPdf = ((ggxVisibleNormalPdf(wo, h, a) * Math.abs(dot(wi, h))) / denom) * (1 - gltfReflectProbability(m, fMax));
    } else if (!m.transmission.refractive) {
      // The thin wall's lobe under its own alphas; the reflection's microfacet normal from the same
      // sampling-square point chose between them (gltf-bsdf.wesl base_eval).
      const at = thinTransmissionAlphas(m);
      if (!smoothAlphas(at)) {
        const [u0, u1] = ggxVisibleNormalSamplePoint(wo, at, h);
        const same = at.x === a.x && at.y === a.y;
        const pf = same ? fMax : maxComponent(gltfDielectricFresnel(m, dot(wo, sampleGgxVisibleNormal(wo, a, u0, u1))));
        const rescale = m.energyCompensation ? lookupGgxAlbedo(wo[2], m.roughness) / lookupGgxAlbedo(wo[2], m.roughness * Math.sqrt(thinSlopeScale(m))) : 1;
        const btdf = (ggxDAniso(h, at) * ggxG2(wo, wm, at)) / (4 * wo[2] * wm[2]);
        f = scale3(m.baseColor, k * rescale * btdf);
        microfacetPdf = (ggxVisibleNormalPdf(wo, h, at) / (4 * dot(wo, h))) * (1 - gltfReflectProbability(m, pf));
      }
    }
  }
  if (m.diffuseTransmission && dt > 0) {
    f = add3(f, scale3(m.diffuseTransmission.color, ((1 - mt) * (1 - t) * dt * weight) / Math.PI));
    diffusePdf = ((1 - w.diffuseReflect) * -wi[2]) / Math.PI;
  }
  return { f, microfacetPdf, diffusePdf };
}

/** f (without the cosine) and the sampling pdf of the composed BSDF, non-delta parts only. */
export function extendedEval(m: GltfBsdfMaterial, wo: Vec3, wi: Vec3): { f: Vec3; pdf: number } {
  if (wo[2] <= 0 || wi[2] === 0) return { f: [0, 0, 0], pdf: 0 };
  if (wi[2] < 0 && !m.transmission && !m.diffuseTransmission) return { f: [0, 0, 0], pdf: 0 };
  const w = gltfLobeWeights(m, wo);
  const base = baseEval(m, w, wo, wi);
  // The layers over the base, outermost first: f = sum_k (prod_{j<k} s_j) f_k + (prod_j s_j) f_base.
  let above: Vec3 = [0, 0, 0];
  let scale = 1;
  let pdf = w.microfacet * base.microfacetPdf + w.diffuse * base.diffusePdf;
  anyLayerReferences.forEach((reference, k) => {
    const params = layerParams(m, reference);
    if (params === undefined) return;
    const e = reference.evalPdf(params, wo, wi);
    above = add3(above, scale3(e.f, scale));
    pdf += w.layers[k]! * e.pdf;
    scale *= reference.scale(params, wo, wi);
  });
  return { f: add3(above, scale3(base.f, scale)), pdf };
}
