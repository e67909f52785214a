/**
 * The KHR_materials_iridescence thin-film Fresnel in double precision (the CPU reference of
 * iridescence.wesl).
 */
import { schlickWeight } from '../../reference/fresnel.ts';
import type { Vec3 } from '../../reference/vector.ts';

/**
 * XYZ -> linear Rec. 709 (the matrix of the KHR_materials_iridescence implementation notes), rows.
 */
const XYZ_TO_REC709 = [
  [3.2404542, -1.5371385, -0.4985314],
  [-0.969266, 1.8760108, 0.041556],
  [0.0556434, -0.2040259, 1.0572252],
] as const;

/**
 * Fourier-space spectral sensitivity of the CIE observer evaluated at optical path difference `opd`
 * (nm) with phase `shift` per channel: Belcour and Barla 2017, section 4, as given in the
 * KHR_materials_iridescence implementation notes (evalSensitivity).
 */
export function iridescenceSensitivity(opd: number, shift: Vec3): Vec3 {
  const phase = 2 * Math.PI * opd * 1e-9;
  const val = [5.4856e-13, 4.4201e-13, 5.2481e-13];
  const pos = [1.681e6, 1.7953e6, 2.2084e6];
  const variance = [4.3278e9, 9.3046e9, 6.6121e9];
  const xyz = [0, 0, 0];
  for (let i = 0; i < 3; i++) {
    xyz[i] = val[i]! * Math.sqrt(2 * Math.PI * variance[i]!) * Math.cos(pos[i]! * phase + shift[i]!) * Math.exp(-phase * phase * variance[i]!);
  }
  xyz[0] += 9.747e-14 * Math.sqrt(2 * Math.PI * 4.5282e9) * Math.cos(2.2399e6 * phase + shift[0]) * Math.exp(-4.5282e9 * phase * phase);
  for (let i = 0; i < 3; i++) xyz[i]! /= 1.0685e-7;
  return XYZ_TO_REC709.map((row) => row[0] * xyz[0]! + row[1] * xyz[1]! + row[2] * xyz[2]!) as unknown as Vec3;
}

/**
 * The thin-film Fresnel of KHR_materials_iridescence ("Iridescence Fresnel", after Belcour and
 * Barla 2017, "A Practical Extension to Microfacet Theory for the Modeling of Varying
 * Iridescence"): the film of index `filmIor` and thickness `thicknessNm` between the outside
 * (`outsideIor`) and a base of reflectance `baseF0`, at incidence cosine `cos1`. As in the Khronos
 * sample viewer, the film's index fades to the outside's as the thickness goes to 0 (smoothstep
 * over 0..30 nm), so a vanishing film leaves the base's reflectance. The result is clamped to
 * [0, 1]: the approximation's spectral integration can overshoot a physical reflectance.
 */
export function iridescentFresnel(outsideIor: number, filmIor: number, baseF0: Vec3, thicknessNm: number, cos1: number): Vec3 {
  const t = Math.min(1, Math.max(0, thicknessNm / 30));
  const film = outsideIor + (filmIor - outsideIor) * (t * t * (3 - 2 * t));
  const sin2T2 = (outsideIor / film) ** 2 * (1 - cos1 * cos1);
  const cos2Sq = 1 - sin2T2;
  if (cos2Sq < 0) return [1, 1, 1];
  const cos2 = Math.sqrt(cos2Sq);
  // First interface (outside -> film).
  const r0 = iorToF0Pair(film, outsideIor);
  const r12 = r0 + (1 - r0) * schlickWeight(cos1);
  const t121 = 1 - r12;
  const phi12 = film < outsideIor ? Math.PI : 0;
  const phi21 = Math.PI - phi12;
  // Second interface (film -> base), per channel.
  const out = [0, 0, 0];
  const r23: number[] = [];
  const phi23: number[] = [];
  for (let c = 0; c < 3; c++) {
    const sqrtF0 = Math.sqrt(Math.min(baseF0[c]! + 1e-4, 0.9999));
    const baseIor = (1 + sqrtF0) / (1 - sqrtF0);
    const r1 = iorToF0Pair(baseIor, film);
    r23.push(r1 + (1 - r1) * schlickWeight(cos2));
    phi23.push(baseIor < film ? Math.PI : 0);
  }
  const opd = 2 * film * thicknessNm * cos2;
  const phi: Vec3 = [phi21 + phi23[0]!, phi21 + phi23[1]!, phi21 + phi23[2]!];
  const r123 = r23.map((r) => Math.min(0.9999, Math.max(1e-5, r12 * r)));
  const rs = r23.map((r, c) => (t121 * t121 * r) / (1 - r123[c]!));
  const i = rs.map((x) => r12 + x);
  const cm = rs.map((x) => x - t121);
  for (let m = 1; m <= 2; m++) {
    for (let c = 0; c < 3; c++) cm[c]! *= Math.sqrt(r123[c]!);
    const sm = iridescenceSensitivity(m * opd, [m * phi[0], m * phi[1], m * phi[2]]);
    for (let c = 0; c < 3; c++) i[c]! += cm[c]! * 2 * sm[c]!;
  }
  for (let c = 0; c < 3; c++) out[c] = Math.min(1, Math.max(0, i[c]!));
  return out as unknown as Vec3;
}

/** ((n_t - n_i) / (n_t + n_i))^2. */
function iorToF0Pair(transmitted: number, incident: number): number {
  return ((transmitted - incident) / (transmitted + incident)) ** 2;
}
