// The BSDF lobes under test: each WESL lobe module with its packed parameters, parameter sets that
// span its behaviour, and an independent double-precision CPU reference of f and pdf. Adding a lobe
// here gives it every generic test of lobe-properties.test.ts.
import { ggxD, gltfBsdfEval, gltfBsdfPdf, smithG1, smithHeightCorrelatedV, type GltfBsdfMaterial, type Vec3 } from '../../src/materials/gltf-bsdf-reference.ts';
import { gltfLobe, type LobeUnderTest } from './bsdf-harness.ts';

export interface LobeCase<P> {
  lobe: LobeUnderTest<P>;
  params: { name: string; value: P }[];
  /** f(wo, wi) without the cosine, and the solid-angle pdf of sampling wi (non-delta parts). */
  reference: { f(p: P, wo: Vec3, wi: Vec3): Vec3; pdf(p: P, wo: Vec3, wi: Vec3): number };
  /** f(wo, wi) = f(wi, wo) (Helmholtz reciprocity). */
  reciprocal: boolean;
  /** Directional albedo never exceeds 1 (the lobe alone conserves energy). */
  energyConserving: boolean;
}

const lambertLobe: LobeUnderTest<{ albedo: Vec3 }> = {
  name: 'Lambert',
  module: 'package::materials::lobes::lambert',
  pack: (p) => [...p.albedo],
};

const ggxReflectionLobe: LobeUnderTest<{ alpha: number }> = {
  name: 'GGX reflection',
  module: 'package::materials::lobes::ggx_reflection',
  pack: (p) => [p.alpha],
};

function upper(wo: Vec3, wi: Vec3): boolean {
  return wo[2] > 0 && wi[2] > 0;
}

function half(wo: Vec3, wi: Vec3): Vec3 {
  const h = [wo[0] + wi[0], wo[1] + wi[1], wo[2] + wi[2]];
  const l = Math.hypot(h[0]!, h[1]!, h[2]!);
  return [h[0]! / l, h[1]! / l, h[2]! / l];
}

export const lobeCases: LobeCase<never>[] = [
  {
    lobe: lambertLobe,
    params: [
      { name: 'white', value: { albedo: [1, 1, 1] } },
      { name: 'coloured', value: { albedo: [0.8, 0.3, 0.05] } },
    ],
    reference: {
      f: (p, wo, wi) => (upper(wo, wi) ? [p.albedo[0] / Math.PI, p.albedo[1] / Math.PI, p.albedo[2] / Math.PI] : [0, 0, 0]),
      pdf: (_p, wo, wi) => (upper(wo, wi) ? wi[2] / Math.PI : 0),
    },
    reciprocal: true,
    energyConserving: true,
  } as LobeCase<{ albedo: Vec3 }>,
  {
    lobe: ggxReflectionLobe,
    params: [
      { name: 'alpha 0.05', value: { alpha: 0.05 } },
      { name: 'alpha 0.3', value: { alpha: 0.3 } },
      { name: 'alpha 1', value: { alpha: 1 } },
    ],
    reference: {
      f: (p, wo, wi) => {
        if (!upper(wo, wi)) return [0, 0, 0];
        const v = ggxD(half(wo, wi)[2], p.alpha) * smithHeightCorrelatedV(wi[2], wo[2], p.alpha);
        return [v, v, v];
      },
      pdf: (p, wo, wi) => (upper(wo, wi) ? (smithG1(wo[2], p.alpha) * ggxD(half(wo, wi)[2], p.alpha)) / (4 * wo[2]) : 0),
    },
    reciprocal: true,
    energyConserving: true,
  } as LobeCase<{ alpha: number }>,
  {
    lobe: gltfLobe,
    params: [
      { name: 'rough dielectric', value: { baseColor: [0.7, 0.5, 0.3], metallic: 0, roughness: 0.6, ior: 1.5 } },
      { name: 'glossy metal', value: { baseColor: [0.95, 0.64, 0.54], metallic: 1, roughness: 0.25, ior: 1.5 } },
      { name: 'half metal', value: { baseColor: [0.2, 0.8, 0.4], metallic: 0.5, roughness: 0.4, ior: 2 } },
    ],
    reference: { f: (p, wo, wi) => gltfBsdfEval(p, wo, wi), pdf: (p, wo, wi) => gltfBsdfPdf(p, wo, wi) },
    reciprocal: true,
    // glTF 2.0 Appendix B's dielectric layering gains energy at grazing angles; its energy bounds
    // are the furnace tests' concern, not a property of the composition's sampling.
    energyConserving: false,
  } as LobeCase<GltfBsdfMaterial>,
] as LobeCase<never>[];
