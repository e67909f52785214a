// The BSDF-harness entries of ggx-dielectric.wesl and ggx-thin-dielectric.wesl (test/materials/lobes.ts
// runs every generic lobe test of lobe-properties.test.ts on them against reference.ts). Test code:
// not part of the package build.
import type { LobeCase } from '../../../../test/materials/lobes.ts';
import type { Alphas } from '../../reference/microfacet.ts';
import type { Vec3 } from '../../reference/vector.ts';
import { ggxDielectric, ggxThinDielectric } from './reference.ts';

interface DielectricParams {
  alpha: number;
  alphaY?: number;
  eta: number;
}

const grey = (v: number): Vec3 => [v, v, v];
const alphas = (p: DielectricParams): Alphas => ({ x: p.alpha, y: p.alphaY ?? p.alpha });

export const ggxDielectricLobeCase: LobeCase<DielectricParams> = {
  lobe: {
    name: 'GGX dielectric (refraction)',
    module: 'package::materials::extensions::transmission::ggx_dielectric',
    pack: (p) => [p.alpha, p.alphaY ?? 0, p.eta],
  },
  params: [
    { name: 'glass alpha 0.3 entering', value: { alpha: 0.3, eta: 1.5 } },
    { name: 'glass alpha 0.5 leaving (total internal reflection)', value: { alpha: 0.5, eta: 1 / 1.5 } },
    { name: 'anisotropic 0.4 x 0.15, eta 1.33', value: { alpha: 0.4, alphaY: 0.15, eta: 1.33 } },
  ],
  reference: {
    f: (p, wo, wi) => grey(ggxDielectric(alphas(p), p.eta, wo, wi).f),
    pdf: (p, wo, wi) => ggxDielectric(alphas(p), p.eta, wo, wi).pdf,
  },
  reciprocal: true,
  transmission: { swap: (p) => ({ ...p, eta: 1 / p.eta }), factor: (p) => p.eta * p.eta },
  // Radiance crossing into a less dense medium is scaled up by 1 / eta^2: the albedo of the
  // radiance BTDF exceeds 1 there though energy is conserved (pbrt-v4 section 9.5.2).
  energyConserving: false,
  // The Fresnel term's slope is unbounded at the critical angle: f32 inputs there differ more.
  tolerance: 3e-3,
};

export const ggxThinDielectricLobeCase: LobeCase<DielectricParams> = {
  lobe: {
    name: 'GGX thin dielectric',
    module: 'package::materials::extensions::transmission::ggx_thin_dielectric',
    pack: (p) => [p.alpha, p.alphaY ?? 0, p.eta],
  },
  params: [
    { name: 'thin alpha 0.2, eta 1.5', value: { alpha: 0.2, eta: 1.5 } },
    { name: 'thin anisotropic 0.5 x 0.2, eta 2', value: { alpha: 0.5, alphaY: 0.2, eta: 2 } },
  ],
  reference: {
    f: (p, wo, wi) => grey(ggxThinDielectric(alphas(p), p.eta, wo, wi).f),
    pdf: (p, wo, wi) => ggxThinDielectric(alphas(p), p.eta, wo, wi).pdf,
  },
  reciprocal: true,
  transmission: {},
  energyConserving: true,
};
