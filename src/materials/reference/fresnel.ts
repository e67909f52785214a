/**
 * Fresnel terms in double precision (the CPU reference of fresnel.wesl): the exact unpolarised
 * dielectric reflectance, Schlick's approximation and the KHR_materials_specular dielectric Fresnel
 * (the iridescence thin film: extensions/iridescence/reference.ts).
 */
import type { Vec3 } from './vector.ts';

// The exact dielectric reflectance is optics every layer shares (the transport branches use it
// too), so its one definition lives in the lower transport layer.
import { fresnelDielectric } from '../../transport/fresnel.ts';

export { fresnelDielectric };

/** Schlick's weight (1 - cos)^5. */
export function schlickWeight(cos: number): number {
  const m = Math.min(1, Math.max(0, 1 - cos));
  return m * m * m * m * m;
}

/** Schlick's approximation with f90 = 1 (glTF 2.0 Appendix B conductor_fresnel). */
export function fresnelSchlick(f0: Vec3, cos: number): Vec3 {
  const w = schlickWeight(cos);
  return [f0[0] + (1 - f0[0]) * w, f0[1] + (1 - f0[1]) * w, f0[2] + (1 - f0[2]) * w];
}

/** F0 of an interface of relative index eta: ((eta - 1) / (eta + 1))^2; eta = Infinity gives 1. */
export function iorToF0(eta: number): number {
  if (!Number.isFinite(eta)) return 1;
  return ((eta - 1) / (eta + 1)) ** 2;
}

/** The dielectric Fresnel of the glTF BSDF with KHR_materials_specular (and KHR_materials_ior = 0). */
export interface DielectricFresnel {
  /** Relative index of refraction seen from the incident side; Infinity for ior = 0 (Fresnel = 1). */
  eta: number;
  /** KHR_materials_specular weight (f90), default 1. */
  specular: number;
  /** KHR_materials_specular F0 colour, default [1, 1, 1]. */
  specularColor: Vec3;
}

/**
 * KHR_materials_specular's Fresnel: F = f0 + (f90 - f0) s(cos) with f0 = min(F0(eta) specularColor, 1)
 * specular and f90 = specular. The glTF text uses Schlick's shape s = (1 - cos)^5; this renderer
 * keeps the exact dielectric curve's shape s = (F(cos) - F0) / (1 - F0), so the defaults reproduce
 * the exact Fresnel term (and total internal reflection) and ior = 1 still reflects nothing. With
 * ior = 0 (KHR_materials_ior's specular-glossiness mode) F0 = 1 and Schlick's shape is used.
 */
export function dielectricFresnelRgb(cos: number, p: DielectricFresnel): Vec3 {
  let f0Ior: number;
  let shape: number;
  if (!Number.isFinite(p.eta)) {
    f0Ior = 1;
    shape = schlickWeight(Math.abs(cos));
  } else {
    f0Ior = iorToF0(p.eta);
    const exact = fresnelDielectric(cos, p.eta);
    shape = f0Ior < 1 ? Math.min(1, Math.max(0, (exact - f0Ior) / (1 - f0Ior))) : 1;
  }
  const f90 = p.specular;
  const out = [0, 0, 0];
  for (let c = 0; c < 3; c++) {
    const f0 = Math.min(f0Ior * p.specularColor[c]!, 1) * p.specular;
    out[c] = f0 + (f90 - f0) * shape;
  }
  return out as unknown as Vec3;
}
