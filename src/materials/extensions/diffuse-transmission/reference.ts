/** The CPU reference of lambert-transmission.wesl (KHR_materials_diffuse_transmission), double precision. */
import { none, type LobeValue } from '../../reference/lobes.ts';
import type { Vec3 } from '../../reference/vector.ts';

/** Lambertian transmission: f = 1 / pi (times its colour) for wi below, cosine-sampled there. */
export function lambertTransmission(wo: Vec3, wi: Vec3): LobeValue {
  if (wo[2] <= 0 || wi[2] >= 0) return none;
  return { f: 1 / Math.PI, pdf: -wi[2] / Math.PI };
}
