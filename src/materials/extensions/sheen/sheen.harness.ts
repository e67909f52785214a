// The BSDF-harness entry of sheen-charlie.wesl (test/materials/lobes.ts runs every generic lobe test
// of lobe-properties.test.ts on it against reference.ts). Test code: not part of the package build.
import type { LobeCase } from '../../../../test/materials/lobes.ts';
import { sheenCharlie } from './reference.ts';

export const sheenLobeCase: LobeCase<{ roughness: number }> = {
  lobe: {
    name: 'Charlie sheen',
    module: 'package::materials::extensions::sheen::sheen_charlie',
    pack: (p) => [p.roughness],
  },
  params: [
    { name: 'sheen roughness 0.3', value: { roughness: 0.3 } },
    { name: 'sheen roughness 0.8', value: { roughness: 0.8 } },
  ],
  reference: {
    f: (p, wo, wi) => {
      const f = sheenCharlie(p.roughness, wo, wi).f;
      return [f, f, f];
    },
    pdf: (p, wo, wi) => sheenCharlie(p.roughness, wo, wi).pdf,
  },
  reciprocal: true,
  // The fitted visibility exceeds 1 at grazing views of low roughness; the composed BSDF divides
  // it out there (gltf-bsdf.wesl), the lobe itself is the specification's.
  energyConserving: false,
};
