/**
 * Exact unpolarised Fresnel reflectance of a dielectric interface (pbrt-v4 `FrDielectric`,
 * section 9.3 "Specular Reflection and Transmission"): the mean of the squared parallel and
 * perpendicular amplitude coefficients. `eta` is the relative IOR eta_t / eta_i; a negative
 * `cosThetaI` means the ray arrives from the transmitted side, so the interface is flipped.
 */
export interface DielectricFresnel {
  /** Fraction of energy reflected, in [0, 1]; 1 under total internal reflection. */
  readonly reflectance: number;
  /** Cosine of the refracted direction (0 under total internal reflection). */
  readonly cosThetaT: number;
  readonly totalInternalReflection: boolean;
  /** Relative IOR actually used after flipping for back-side incidence. */
  readonly eta: number;
}

export function fresnelDielectric(cosThetaI: number, eta: number): DielectricFresnel {
  let cosI = Math.min(1, Math.max(-1, cosThetaI));
  let e = eta;
  if (cosI < 0) {
    e = 1 / e;
    cosI = -cosI;
  }
  const sin2I = Math.max(0, 1 - cosI * cosI);
  const sin2T = sin2I / (e * e);
  // Snell's law has no real solution: total internal reflection.
  if (sin2T >= 1) return { reflectance: 1, cosThetaT: 0, totalInternalReflection: true, eta: e };
  const cosT = Math.sqrt(Math.max(0, 1 - sin2T));
  const rParl = (e * cosI - cosT) / (e * cosI + cosT);
  const rPerp = (cosI - e * cosT) / (cosI + e * cosT);
  return { reflectance: (rParl * rParl + rPerp * rPerp) / 2, cosThetaT: cosT, totalInternalReflection: false, eta: e };
}
