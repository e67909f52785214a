// The BSDF-harness entry of lambert-transmission.wesl (test/materials/lobes.ts runs every generic
// lobe test of lobe-properties.test.ts on it against reference.ts). Test code: not part of the
// package build.
import type { LobeCase } from '../../../../test/materials/lobes.ts';
import type { Vec3 } from '../../reference/vector.ts';
import { lambertTransmission } from './reference.ts';

export const lambertTransmissionLobeCase: LobeCase<{ color: Vec3 }> = {
  lobe: {
    name: 'Lambert transmission',
    module: 'package::materials::extensions::diffuse_transmission::lambert_transmission',
    pack: (p) => [...p.color],
  },
  params: [{ name: 'tinted', value: { color: [0.9, 0.5, 0.2] } }],
  reference: {
    f: (p, wo, wi) => {
      const v = lambertTransmission(wo, wi).f;
      return [p.color[0] * v, p.color[1] * v, p.color[2] * v];
    },
    pdf: (_p, wo, wi) => lambertTransmission(wo, wi).pdf,
  },
  reciprocal: true,
  transmission: {},
  energyConserving: true,
};
