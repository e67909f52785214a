// The BSDF lobes under test: each WESL lobe module with its packed parameters, parameter sets that
// span its behaviour, and an independent double-precision CPU reference of f and pdf. Adding a lobe
// here gives it every generic test of lobe-properties.test.ts. The lobes of KHR extensions keep
// their entries beside their modules (src/materials/extensions/<name>/<name>.harness.ts, found by
// name).
import { ggxD, gltfBsdfEval, gltfBsdfPdf, smithG1, smithHeightCorrelatedV, type GltfBsdfMaterial, type Vec3 } from '../../src/materials/gltf-bsdf-reference.ts';
import { readdirSync } from 'node:fs';
import { ggxReflection } from '../../src/materials/reference/lobes.ts';
import type { Alphas } from '../../src/materials/reference/microfacet.ts';
import { gltfExtensionLobe, gltfLobe, type LobeUnderTest } from './bsdf-harness.ts';
import { materialLayerReferences } from '../../src/materials/material-layers.generated.ts';

export interface LobeCase<P> {
  lobe: LobeUnderTest<P>;
  params: { name: string; value: P }[];
  /** f(wo, wi) without the cosine, and the solid-angle pdf of sampling wi (non-delta parts). */
  reference: { f(p: P, wo: Vec3, wi: Vec3): Vec3; pdf(p: P, wo: Vec3, wi: Vec3): number };
  /** f(wo, wi) = f(wi, wo) for reflection (Helmholtz reciprocity). */
  reciprocal: boolean;
  /**
   * Transmission lobes: wi may lie below the surface (tests sample and integrate over the sphere).
   * `swap` gives the parameters seen from the other side and `factor` the generalised reciprocity
   * f(-wi, -wo; swap(p)) = factor(p) f(wo, wi; p) of radiance transport (Veach 1997, section 5.2:
   * eta^2 for refraction, 1 for thin and diffuse transmission); absent when the lobe has none.
   */
  transmission?: { swap?(p: P): P; factor?(p: P): number };
  /** Directional albedo never exceeds 1 (the lobe alone conserves energy). */
  energyConserving: boolean;
  /** Relative tolerance of eval / pdf against the reference (f32 against f64); default 2e-4. */
  tolerance?: number;
}

const lambertLobe: LobeUnderTest<{ albedo: Vec3 }> = {
  name: 'Lambert',
  module: 'package::materials::lobes::lambert',
  pack: (p) => [...p.albedo],
};

const ggxReflectionLobe: LobeUnderTest<{ alpha: number; alphaY?: number }> = {
  name: 'GGX reflection',
  module: 'package::materials::lobes::ggx_reflection',
  pack: (p) => [p.alpha, p.alphaY ?? 0],
};

function upper(wo: Vec3, wi: Vec3): boolean {
  return wo[2] > 0 && wi[2] > 0;
}

function half(wo: Vec3, wi: Vec3): Vec3 {
  const h = [wo[0] + wi[0], wo[1] + wi[1], wo[2] + wi[2]];
  const l = Math.hypot(h[0]!, h[1]!, h[2]!);
  return [h[0]! / l, h[1]! / l, h[2]! / l];
}

const grey = (v: number): Vec3 => [v, v, v];
const alphas = (p: { alpha: number; alphaY?: number }): Alphas => ({ x: p.alpha, y: p.alphaY ?? p.alpha });

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
      { name: 'anisotropic 0.6 x 0.1', value: { alpha: 0.6, alphaY: 0.1 } },
    ],
    reference: {
      f: (p, wo, wi) => {
        if (!upper(wo, wi)) return [0, 0, 0];
        if (p.alphaY === undefined) {
          // The isotropic case in Appendix B's own scalar forms.
          const v = ggxD(half(wo, wi)[2], p.alpha) * smithHeightCorrelatedV(wi[2], wo[2], p.alpha);
          return grey(v);
        }
        return grey(ggxReflection(alphas(p), wo, wi).f);
      },
      pdf: (p, wo, wi) => {
        if (!upper(wo, wi)) return 0;
        if (p.alphaY === undefined) return (smithG1(wo[2], p.alpha) * ggxD(half(wo, wi)[2], p.alpha)) / (4 * wo[2]);
        return ggxReflection(alphas(p), wo, wi).pdf;
      },
    },
    reciprocal: true,
    energyConserving: true,
  } as LobeCase<{ alpha: number; alphaY?: number }>,
  ...(await extensionLobeCases()),
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
  ...extensionCases(),
] as LobeCase<never>[];

/**
 * The lobe cases kept beside the KHR extensions' lobe modules: every export of each
 * src/materials/extensions/<name>/*.harness.ts (found by name, so a new extension's entry needs no
 * line here).
 */
async function extensionLobeCases(): Promise<LobeCase<never>[]> {
  const root = new URL('../../src/materials/extensions/', import.meta.url);
  const cases: LobeCase<never>[] = [];
  for (const dir of readdirSync(root, { withFileTypes: true }).filter((d) => d.isDirectory()).map((d) => d.name).sort()) {
    for (const file of readdirSync(new URL(`${dir}/`, root)).filter((f) => f.endsWith('.harness.ts')).sort()) {
      const entries = (await import(new URL(`${dir}/${file}`, root).href)) as Record<string, LobeCase<never>>;
      cases.push(...Object.values(entries));
    }
  }
  return cases;
}

/** The composed glTF BSDF with KHR extensions, one compiled kernel per feature set. */
function extensionCases(): LobeCase<GltfBsdfMaterial>[] {
  const reference = { f: (p: GltfBsdfMaterial, wo: Vec3, wi: Vec3) => gltfBsdfEval(p, wo, wi), pdf: (p: GltfBsdfMaterial, wo: Vec3, wi: Vec3) => gltfBsdfPdf(p, wo, wi) };
  const tilted = (x: number, y: number): Vec3 => {
    const l = Math.hypot(x, y, 1);
    return [x / l, y / l, 1 / l];
  };
  return [
    {
      lobe: gltfExtensionLobe('glTF + transmission, volume, specular', ['FEATURE_TRANSMISSION', 'FEATURE_VOLUME', 'FEATURE_SPECULAR']),
      params: [
        { name: 'rough glass entering', value: { baseColor: [1, 1, 1], metallic: 0, roughness: 0.5, ior: 1.5, transmission: { factor: 1, refractive: true } } },
        { name: 'rough tinted glass leaving', value: { baseColor: [0.9, 0.8, 0.6], metallic: 0, roughness: 0.4, ior: 1 / 1.5, transmission: { factor: 1, refractive: true } } },
        // A thin wall of ior 1.2: its transmitted lobe's slopes scale by 0.4 (prisms of index 1.2).
        { name: 'thin wall, ior 1.2', value: { baseColor: [0.8, 0.9, 1], metallic: 0, roughness: 0.6, ior: 1.2, transmission: { factor: 1, refractive: false } } },
        {
          name: 'thin half-transmissive, KHR specular',
          value: { baseColor: [0.9, 0.6, 0.3], metallic: 0.2, roughness: 0.45, ior: 1.5, transmission: { factor: 0.7, refractive: false }, specular: { factor: 0.8, color: [1, 0.9, 1.4] } },
        },
      ],
      reference,
      reciprocal: false,
      transmission: {},
      energyConserving: false,
    },
    {
      lobe: gltfExtensionLobe('glTF + diffuse transmission, clearcoat, anisotropy', ['FEATURE_DIFFUSE_TRANSMISSION', 'FEATURE_CLEARCOAT', 'FEATURE_ANISOTROPY']),
      params: [
        {
          name: 'leaf under a coat',
          value: { baseColor: [0.4, 0.7, 0.3], metallic: 0, roughness: 0.6, ior: 1.5, diffuseTransmission: { factor: 0.5, color: [0.9, 0.8, 0.2] }, clearcoat: { factor: 0.8, roughness: 0.3, normal: tilted(0.2, -0.1) } },
        },
        { name: 'brushed metal under a smooth coat', value: { baseColor: [0.9, 0.9, 0.95], metallic: 1, roughness: 0.35, ior: 1.5, anisotropy: 0.8, clearcoat: { factor: 1, roughness: 0 } } },
      ],
      reference,
      reciprocal: false,
      transmission: {},
      energyConserving: false,
    },
    {
      lobe: gltfExtensionLobe('glTF + sheen, iridescence', ['FEATURE_SHEEN', 'FEATURE_IRIDESCENCE']),
      params: [
        { name: 'velvet', value: { baseColor: [0.3, 0.05, 0.1], metallic: 0, roughness: 0.8, ior: 1.5, sheen: { color: [0.9, 0.4, 0.6], roughness: 0.5 } } },
        { name: 'iridescent metal', value: { baseColor: [0.8, 0.6, 0.3], metallic: 1, roughness: 0.3, ior: 1.5, iridescence: { factor: 0.9, thickness: 380, ior: 1.3 } } },
        { name: 'iridescent dielectric', value: { baseColor: [0.1, 0.1, 0.1], metallic: 0, roughness: 0.25, ior: 1.6, iridescence: { factor: 1, thickness: 520, ior: 1.8 } } },
      ],
      reference,
      reciprocal: false,
      energyConserving: false,
    },
    // Every layer of the registry over a rough dielectric base, with the examples its reference
    // gives: a new layer is tested against its reference without a case of its own.
    {
      lobe: gltfExtensionLobe('glTF under each registry layer', materialLayerReferences.map((r) => r.feature)),
      params: materialLayerReferences.flatMap((r) =>
        r.examples.map((example) => ({ name: `${r.key}: ${example.name}`, value: { baseColor: [0.6, 0.5, 0.4], metallic: 0, roughness: 0.5, ior: 1.5, [r.key]: example.value } as GltfBsdfMaterial })),
      ),
      reference,
      reciprocal: false,
      energyConserving: false,
    },
    {
      lobe: gltfExtensionLobe('glTF + energy compensation', ['FEATURE_ENERGY_COMPENSATION', 'FEATURE_TRANSMISSION', 'FEATURE_VOLUME']),
      params: [
        { name: 'compensated rough dielectric', value: { baseColor: [0.8, 0.8, 0.8], metallic: 0, roughness: 0.7, ior: 1.5, energyCompensation: true } },
        { name: 'compensated rough metal', value: { baseColor: [0.9, 0.7, 0.5], metallic: 1, roughness: 0.8, ior: 1.5, energyCompensation: true } },
        { name: 'compensated rough glass', value: { baseColor: [1, 1, 1], metallic: 0, roughness: 0.6, ior: 1.5, transmission: { factor: 1, refractive: true }, energyCompensation: true } },
      ],
      reference,
      reciprocal: false,
      transmission: {},
      energyConserving: true,
    },
  ];
}
