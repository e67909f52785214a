/**
 * Precomputed directional albedos of the microfacet lobes, computed deterministically in double
 * precision when a scene first needs them (and kept for the process), packed into the material
 * heap and read by energy-tables.wesl with linear interpolation:
 *
 * - `ggx`: E(mu, r) of GGX reflection with F = 1 (the single-scattering energy Kulla and Conty 2017
 *   and Turquin 2019 compensate), then the cosine-weighted averages 2 int E(mu) mu dmu per r;
 * - `dielectric`: E(mu, r, eta) of dielectric GGX reflection with the exact Fresnel term (what a
 *   specular layer reflects: the albedo scaling of the layer below it), then averages per (eta, r);
 * - `dielectricTransmission`: E(mu, r, eta) of a rough dielectric interface, reflection plus
 *   transmitted energy (Turquin's normalisation of rough glass);
 * - `clearcoat`: E(mu, r) of the KHR_materials_clearcoat layer (dielectric reflection at ior 1.5);
 * - `sheen`: E(mu, r) of the Charlie sheen lobe (KHR_materials_sheen albedo scaling).
 *
 * Axes: mu_i = i / (n - 1) (evaluated at >= 1e-3), perceptual roughness r_j = j / (n - 1)
 * (alpha = r^2), and for dielectrics y_k = -1 + 2 k / (n - 1) = sign(x) x^2 with
 * x = (eta - 1) / (eta + 1): |y| is the interface's F0, in which the albedos are nearly linear,
 * and y < 0 covers eta < 1 (leaving a denser medium); y = -1 and 1 are the limits eta = 0 and
 * infinity, where F = 1.
 */
import {
  DIELECTRIC_TABLE_ETA_NODES,
  DIELECTRIC_TABLE_MU_NODES,
  DIELECTRIC_TABLE_ROUGHNESS_NODES,
  ENERGY_TABLE_MU_NODES,
  ENERGY_TABLE_ROUGHNESS_NODES,
  SHEEN_TABLE_NODES,
} from '../../gpu-layout/constants.ts';
import { fresnelDielectric } from '../reference/fresnel.ts';
import { ggxG2, reflect, refract, type Alphas } from '../reference/microfacet.ts';
import { deltaAlpha } from '../reference/lobes.ts';
import { charlieLambda, sheenAlpha } from '../extensions/sheen/sheen-charlie.ts';
import { dot, type Vec3 } from '../reference/vector.ts';

export interface AlbedoTables {
  /** ENERGY_TABLE_ROUGHNESS_NODES x ENERGY_TABLE_MU_NODES values (r-major), then one average per r. */
  readonly ggx: Float32Array;
  /** ETA x ROUGHNESS x MU values (eta-major), then ETA x ROUGHNESS averages. */
  readonly dielectric: Float32Array;
  /** ETA x ROUGHNESS x MU values. */
  readonly dielectricTransmission: Float32Array;
  /** ENERGY_TABLE_ROUGHNESS_NODES x ENERGY_TABLE_MU_NODES values at ior 1.5. */
  readonly clearcoat: Float32Array;
  /** SHEEN_TABLE_NODES (roughness) x SHEEN_TABLE_NODES (mu). */
  readonly sheen: Float32Array;
}

/** Node value of axis node i of n over [0, 1]. */
export const unitNode = (i: number, n: number): number => i / (n - 1);
/** Relative index of refraction of dielectric-table node k: y = sign(x) sqrt(|x|) uniform in [-1, 1], eta = (1 + x) / (1 - x). */
export function etaNode(k: number, n = DIELECTRIC_TABLE_ETA_NODES): number {
  const y = -1 + (2 * k) / (n - 1);
  if (y <= -1) return 0;
  if (y >= 1) return Infinity;
  const x = Math.sign(y) * y * y;
  return (1 + x) / (1 - x);
}

/** The dielectric tables' axis coordinate of a relative index: sign(x) sqrt(|x|), x = (eta - 1) / (eta + 1) (eta = 0: -1, Infinity: 1). */
export function etaAxis(eta: number): number {
  if (!Number.isFinite(eta)) return 1;
  const x = (eta - 1) / (eta + 1);
  return Math.sign(x) * Math.sqrt(Math.abs(x));
}

/** KHR_materials_clearcoat's fixed index of refraction. */
export const clearcoatIor = 1.5;

const minMu = 1e-3;

function viewAt(mu: number): Vec3 {
  const m = Math.max(mu, minMu);
  return [Math.sqrt(1 - m * m), 0, m];
}

/** Gauss-Legendre nodes and weights on [0, 1]. */
function gaussLegendre(n: number): { x: number[]; w: number[] } {
  const x: number[] = [];
  const w: number[] = [];
  for (let i = 1; i <= n; i++) {
    let z = Math.cos((Math.PI * (i - 0.25)) / (n + 0.5));
    let dp = 0;
    for (let iter = 0; iter < 100; iter++) {
      let p0 = 1;
      let p1 = 0;
      for (let j = 1; j <= n; j++) {
        const p2 = p1;
        p1 = p0;
        p0 = ((2 * j - 1) * z * p1 - (j - 1) * p2) / j;
      }
      dp = (n * (z * p0 - p1)) / (z * z - 1);
      const dz = p0 / dp;
      z -= dz;
      if (Math.abs(dz) < 1e-15) break;
    }
    x.push(0.5 * (1 - z));
    w.push(1 / ((1 - z * z) * dp * dp));
  }
  return { x, w };
}

/**
 * Single-scattering albedos of the GGX microfacet lobes at view wo (isotropic alpha), integrated
 * over microfacet normals h = (theta, phi) in GGX's own coordinates: u = tan^2 / (alpha^2 +
 * tan^2), for which D(h) cos sin dtheta dphi = du dphi / 2 pi. Reflection (weight F G2) is
 * integrated up to the angle where the reflected direction meets the horizon, found in closed
 * form for each phi (wi.z = 0 at tan(2 theta) = -cos_o / (sin_o cos phi)), so the Gauss-Legendre
 * rule never straddles a discontinuity; transmission (weight (1 - F) G2) over the normals facing
 * wo. Both are the visible-normal integrals of Heitz 2018 eq. 17 (D_wo = G1 wo.h D / cos_o).
 */
function microfacetAlbedo(mu: number, alpha: number, eta: number | null, withFresnel: boolean): { reflection: number; transmission: number } {
  const wo = viewAt(mu);
  const a: Alphas = { x: alpha, y: alpha };
  const gl = microfacetQuadrature();
  const glPhi = microfacetPhiQuadrature();
  const a2 = alpha * alpha;
  let reflection = 0;
  let transmission = 0;
  for (let p = 0; p < glPhi.x.length; p++) {
    // phi over [0, pi] by symmetry.
    const phi = Math.PI * glPhi.x[p]!;
    const cp = Math.cos(phi);
    const sp = Math.sin(phi);
    const aa = wo[0] * cp;
    const thetaReflect = 0.5 * Math.atan2(aa, wo[2]) + Math.PI / 4;
    // wo.h > 0 for theta below this (pi/2 when wo.h never vanishes).
    const thetaFacing = aa < 0 ? Math.atan2(wo[2], -aa) : Math.PI / 2;
    const integrate = (thetaMax: number, weight: (h: Vec3) => number): number => {
      // In s = sqrt(1 - u) the measure du / cos(theta) = 2 sqrt(s^2 + alpha^2 (1 - s^2)) ds has no
      // singularity at grazing normals (u -> 1), so Gauss-Legendre converges there too.
      const t = Math.tan(Math.min(thetaMax, Math.PI / 2)) ** 2;
      const sMin = thetaMax >= Math.PI / 2 ? 0 : Math.sqrt(a2 / (a2 + t));
      let sum = 0;
      for (let q = 0; q < gl.x.length; q++) {
        const sq = sMin + (1 - sMin) * gl.x[q]!;
        const cosT = sq / Math.sqrt(sq * sq + a2 * (1 - sq * sq));
        const sinT = Math.sqrt(Math.max(0, 1 - cosT * cosT));
        const h: Vec3 = [sinT * cp, sinT * sp, cosT];
        const oh = dot(wo, h);
        if (oh <= 0) continue;
        sum += gl.w[q]! * weight(h) * (oh / wo[2]) * 2 * Math.sqrt(sq * sq + a2 * (1 - sq * sq));
      }
      return sum * (1 - sMin);
    };
    reflection += glPhi.w[p]! * integrate(thetaReflect, (h) => {
      const wr = reflect(wo, h);
      if (wr[2] <= 0) return 0;
      const f = !withFresnel || eta === null || eta === 0 || eta === Infinity ? 1 : fresnelDielectric(dot(wo, h), eta);
      return f * ggxG2(wo, wr, a);
    });
    if (eta !== null && eta !== 0 && eta !== Infinity) {
      transmission += glPhi.w[p]! * integrate(thetaFacing, (h) => {
        const f = fresnelDielectric(dot(wo, h), eta);
        if (f >= 1) return 0;
        const wt = refract(wo, h, eta);
        return wt && wt[2] < 0 ? (1 - f) * ggxG2(wo, wt, a) : 0;
      });
    }
  }
  // int dphi / 2 pi over [0, 2 pi] = 2 * (pi / 2 pi) * int over [0, 1] of the phi / pi variable.
  return { reflection, transmission };
}

let microfacetGl: { x: number[]; w: number[] } | undefined;
let microfacetPhiGl: { x: number[]; w: number[] } | undefined;
function microfacetQuadrature(): { x: number[]; w: number[] } {
  microfacetGl ??= gaussLegendre(MICROFACET_THETA_NODES);
  return microfacetGl;
}
function microfacetPhiQuadrature(): { x: number[]; w: number[] } {
  microfacetPhiGl ??= gaussLegendre(MICROFACET_PHI_NODES);
  return microfacetPhiGl;
}
/** Gauss-Legendre orders of the microfacet albedo quadrature (in s and phi). */
const MICROFACET_THETA_NODES = 16;
const MICROFACET_PHI_NODES = 12;

function alphasOf(r: number): Alphas {
  const alpha = r * r;
  return { x: alpha, y: alpha };
}

/** E(mu) of GGX reflection with F = 1 (exactly 1 for a smooth, delta lobe). */
export function ggxAlbedo(mu: number, r: number): number {
  const a = alphasOf(r);
  if (a.x < deltaAlpha) return 1;
  return microfacetAlbedo(mu, a.x, null, false).reflection;
}

/** E(mu) of dielectric GGX reflection, F = exact Fresnel of relative index eta (0, Infinity: F = 1). */
export function dielectricReflectionAlbedo(mu: number, r: number, eta: number): number {
  const a = alphasOf(r);
  if (a.x < deltaAlpha) return eta === 0 || eta === Infinity ? 1 : fresnelDielectric(Math.max(mu, minMu), eta);
  if (eta === 0 || eta === Infinity) return ggxAlbedo(mu, r);
  return microfacetAlbedo(mu, a.x, eta, true).reflection;
}

/** E(mu) of a rough dielectric interface: reflected plus transmitted energy (1 when smooth). */
export function dielectricInterfaceAlbedo(mu: number, r: number, eta: number): number {
  const a = alphasOf(r);
  if (a.x < deltaAlpha) return 1;
  if (eta === 0 || eta === Infinity) return ggxAlbedo(mu, r);
  // An index-matched interface is the model's eta -> 1 limit.
  const e = eta === 1 ? 1 + 1e-6 : eta;
  const v = microfacetAlbedo(mu, a.x, e, true);
  return v.reflection + v.transmission;
}

/** E(mu) of the Charlie sheen lobe: Gauss-Legendre product quadrature over (cos theta_i, phi). */
export function sheenAlbedo(mu: number, sheenRoughness: number): number {
  const wo = viewAt(mu);
  const gl = sheenQuadrature();
  const alpha = sheenAlpha(sheenRoughness);
  const lambdaO = charlieLambda(wo[2], alpha);
  const dScale = (2 + 1 / alpha) / (2 * Math.PI);
  let sum = 0;
  for (let i = 0; i < gl.x.length; i++) {
    const ci = gl.x[i]!;
    const si = Math.sqrt(Math.max(0, 1 - ci * ci));
    // f cos_i = D V cos_i with V = 1 / ((1 + Lambda_o + Lambda_i) 4 cos_o cos_i).
    const vCos = 1 / ((1 + lambdaO + charlieLambda(ci, alpha)) * 4 * wo[2]);
    let row = 0;
    for (let j = 0; j < gl.x.length; j++) {
      // phi over [0, pi] (the lobe is symmetric in phi), twice.
      const phi = Math.PI * gl.x[j]!;
      const hx = wo[0] + si * Math.cos(phi);
      const hy = si * Math.sin(phi);
      const hz = wo[2] + ci;
      const sin2 = (hx * hx + hy * hy) / (hx * hx + hy * hy + hz * hz);
      row += gl.w[j]! * dScale * Math.pow(sin2, 0.5 / alpha);
    }
    sum += gl.w[i]! * row * vCos;
  }
  return sum * 2 * Math.PI;
}

let sheenGl: { x: number[]; w: number[] } | undefined;
function sheenQuadrature(): { x: number[]; w: number[] } {
  sheenGl ??= gaussLegendre(48);
  return sheenGl;
}

/**
 * Cosine-weighted average 2 int_0^1 E(mu) mu dmu of the piecewise-linear interpolant of the node
 * values (what the GPU lookups see), integrated exactly: albedo scaling normalised with it keeps a
 * Lambertian base's energy exact for the interpolated table.
 */
export function linearCosineAverage(values: ArrayLike<number>): number {
  const n = values.length;
  const h = 1 / (n - 1);
  let s = 0;
  for (let i = 0; i + 1 < n; i++) {
    const m0 = i * h;
    const e0 = values[i]!;
    const e1 = values[i + 1]!;
    // int_{m0}^{m0+h} (e0 + (e1 - e0) t / h) 2 mu dmu, mu = m0 + t.
    s += 2 * (e0 * (m0 * h + (h * h) / 2) + (e1 - e0) * ((m0 * h) / 2 + (h * h) / 3));
  }
  return s;
}

function buildGgx(clearcoat: boolean): Float32Array {
  const nr = ENERGY_TABLE_ROUGHNESS_NODES;
  const nm = ENERGY_TABLE_MU_NODES;
  const out = new Float32Array(nr * nm + (clearcoat ? 0 : nr));
  for (let j = 0; j < nr; j++) {
    const r = unitNode(j, nr);
    for (let i = 0; i < nm; i++) out[j * nm + i] = clearcoat ? dielectricReflectionAlbedo(unitNode(i, nm), r, clearcoatIor) : ggxAlbedo(unitNode(i, nm), r);
    if (!clearcoat) out[nr * nm + j] = linearCosineAverage(out.subarray(j * nm, (j + 1) * nm));
  }
  return out;
}

function buildDielectric(transmission: boolean): Float32Array {
  const ne = DIELECTRIC_TABLE_ETA_NODES;
  const nr = DIELECTRIC_TABLE_ROUGHNESS_NODES;
  const nm = DIELECTRIC_TABLE_MU_NODES;
  const out = new Float32Array(ne * nr * nm + (transmission ? 0 : ne * nr));
  const albedo = transmission ? dielectricInterfaceAlbedo : dielectricReflectionAlbedo;
  for (let k = 0; k < ne; k++) {
    const eta = etaNode(k, ne);
    for (let j = 0; j < nr; j++) {
      const r = unitNode(j, nr);
      for (let i = 0; i < nm; i++) out[(k * nr + j) * nm + i] = albedo(unitNode(i, nm), r, eta);
      if (!transmission) out[ne * nr * nm + k * nr + j] = linearCosineAverage(out.subarray((k * nr + j) * nm, (k * nr + j + 1) * nm));
    }
  }
  return out;
}

function buildSheen(): Float32Array {
  const n = SHEEN_TABLE_NODES;
  const out = new Float32Array(n * n);
  for (let j = 0; j < n; j++) for (let i = 0; i < n; i++) out[j * n + i] = sheenAlbedo(unitNode(i, n), unitNode(j, n));
  return out;
}

const cache: Partial<Record<keyof AlbedoTables, Float32Array>> = {};

/** The tables named (computed on first use, then shared by every scene of the process). */
export function albedoTable(name: keyof AlbedoTables): Float32Array {
  const hit = cache[name];
  if (hit) return hit;
  const builders: Record<keyof AlbedoTables, () => Float32Array> = {
    ggx: () => buildGgx(false),
    dielectric: () => buildDielectric(false),
    dielectricTransmission: () => buildDielectric(true),
    clearcoat: () => buildGgx(true),
    sheen: buildSheen,
  };
  const built = builders[name]();
  cache[name] = built;
  return built;
}
