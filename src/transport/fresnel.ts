/**
 * Unpolarised Fresnel reflectance of a smooth dielectric (pbrt-v4 FrDielectric, section 9.3):
 * cosThetaI on the incident side (negative: from inside, eta inverted), eta = n_t / n_i.
 */
export function fresnelDielectric(cosThetaI: number, eta: number): number {
  // An index-matched interface reflects nothing (the limit of the formulas below, without rounding noise).
  if (eta === 1) return 0;
  let cosI = Math.min(1, Math.max(-1, cosThetaI));
  let e = eta;
  if (cosI < 0) {
    e = 1 / e;
    cosI = -cosI;
  }
  const sin2T = (1 - cosI * cosI) / (e * e);
  if (sin2T >= 1) return 1;
  const cosT = Math.sqrt(1 - sin2T);
  const rParl = (e * cosI - cosT) / (e * cosI + cosT);
  const rPerp = (cosI - e * cosT) / (cosI + e * cosT);
  return 0.5 * (rParl * rParl + rPerp * rPerp);
}

/**
 * A dielectric interface crossing: Snell's law for the refracted cosine and total internal
 * reflection, plus the exact unpolarised Fresnel reflectance `fresnelDielectric` above, the package's
 * one definition (the BSDF reference in src/materials uses it too), so the transport branches and
 * the BSDF reference cannot disagree. `eta` is eta_t / eta_i; a negative `cosThetaI` means the ray
 * arrives from the transmitted side, so the interface is flipped.
 */
export interface DielectricInterface {
  /** Fraction of energy reflected, in [0, 1]; 1 under total internal reflection. */
  readonly reflectance: number;
  /** Cosine of the refracted direction (0 under total internal reflection). */
  readonly cosThetaT: number;
  readonly totalInternalReflection: boolean;
  /** Relative IOR actually used after flipping for back-side incidence. */
  readonly eta: number;
}

export function dielectricInterface(cosThetaI: number, eta: number): DielectricInterface {
  let cosI = Math.min(1, Math.max(-1, cosThetaI));
  let e = eta;
  if (cosI < 0) {
    e = 1 / e;
    cosI = -cosI;
  }
  const sin2T = Math.max(0, 1 - cosI * cosI) / (e * e);
  // Snell's law has no real solution: total internal reflection.
  if (sin2T >= 1) return { reflectance: 1, cosThetaT: 0, totalInternalReflection: true, eta: e };
  return { reflectance: fresnelDielectric(cosI, e), cosThetaT: Math.sqrt(Math.max(0, 1 - sin2T)), totalInternalReflection: false, eta: e };
}
