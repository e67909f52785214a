import { describe, fail, requireVec } from '../errors/validate.ts';
import { allocateStructArray, writeStruct } from '../gpu-layout/struct-layout.ts';
import type { Vec3Input } from '../scene/types.ts';
import { environmentRadiance } from './environment-map.ts';
import { environmentPdf, sampleEnvironment, type EnvironmentSampler } from './environment-sampling.ts';
import { add, cross, dot, length, luminance, normalize, scale, sub, type Vec3 } from './vec3.ts';
import { environmentPortalLayout } from '../gpu-layout/records.ts';
import { requireKnownKeys } from './known-keys.ts';

export { environmentPortalLayout };

/**
 * Environment portals (`environmentPortals`, `environmentPortalMode`): rectangles such as windows
 * through which the environment lights an interior. Portals change only how the environment is
 * *sampled*, never the radiance it contributes, so the image's expected value is the same with
 * and without them.
 *
 * Sampling follows Bitterli, Novak, Jarosz 2015, "Portal-Masked Environment Map Sampling" (EGSR), in
 * the form of pbrt-v4's PortalImageInfiniteLight (4th ed., sec. 12.5.4): the environment is
 * resampled into each portal's *rectified* parametrisation, (u, v) = ((alpha + pi/2) / pi,
 * (beta + pi/2) / pi) with alpha = atan2(w.x, w.z), beta = atan2(w.y, w.z) in the portal's frame
 * (z = outward normal), where the directions from any point behind the portal through it form an
 * axis-aligned rectangle (the "window"). A summed-area table of the rectified luminance x
 * d omega / d(u, v) gives the exact integral over any window, and sampling inverts it by bisection
 * (pbrt's WindowedPiecewiseConstant2D): marginal in u over the window, then conditional in v within
 * the chosen column; the density is piecewise constant per rectified cell.
 *
 * Radiance always comes from the environment map's own (bilinear) lookup; the rectified image only
 * shapes the density, which gets a floor of 1e-3 x its mean so that every direction through a
 * portal keeps a positive density (a sampling density, no energy is added).
 *
 * Several portals: a portal is chosen in proportion to its window integral (the approximate
 * radiance it lets through), so pdf(w) = sum over portals that w passes through of
 * f_k(uv_k) / J_k(uv_k) / sum_k window integral_k.
 *
 * Modes:
 * - 'guide' (default): a defensive mixture: with probability PORTAL_GUIDE_PROBABILITY through the
 *   portals, else the environment's own importance sampling; unbiased whatever the portals cover.
 * - 'guide-and-gate': only through portals (no density outside them). Light sampling then never
 *   proposes directions outside the portals; combined by MIS with BSDF sampling, whose rays still
 *   collect environment radiance wherever they escape, the estimator stays unbiased, and it is
 *   efficient when the portals cover every opening (the scene's walls block the rest anyway).
 * From a point with no portal in view (e.g. outdoors) 'guide' falls back to plain environment
 * sampling and 'guide-and-gate' has no environment sample (BSDF sampling covers it).
 */

export interface EnvironmentPortalInput {
  center: Vec3Input;
  /** Full, orthogonal edges; cross(edgeU, edgeV) points out of the room, towards the environment. */
  edgeU: Vec3Input;
  edgeV: Vec3Input;
}

export type EnvironmentPortalMode = 'guide' | 'guide-and-gate';

export interface Portal {
  corner: Vec3;
  edgeU: Vec3;
  edgeV: Vec3;
  /** Frame: x = edgeU / |edgeU|, y = edgeV / |edgeV|, z = outward normal. */
  x: Vec3;
  y: Vec3;
  z: Vec3;
}

const CODE = 'INVALID_ENVIRONMENT';

/** Validates `environmentPortals`: an array of orthogonal-edged rectangles. */
export function validateEnvironmentPortals(input: unknown, field = 'environmentPortals'): Portal[] {
  if (!Array.isArray(input)) fail(CODE, field, `expected an array of portals, got ${describe(input)}`);
  return input.map((p: unknown, i) => {
    const f = `${field}[${i}]`;
    if (typeof p !== 'object' || p === null) fail(CODE, f, `expected an object, got ${describe(p)}`);
    const v = p as Record<string, unknown>;
    requireKnownKeys(v, ['center', 'edgeU', 'edgeV'], f, CODE);
    const center = requireVec(v.center, 3, `${f}.center`, CODE) as Vec3;
    const edgeU = requireVec(v.edgeU, 3, `${f}.edgeU`, CODE) as Vec3;
    const edgeV = requireVec(v.edgeV, 3, `${f}.edgeV`, CODE) as Vec3;
    const lu = length(edgeU);
    const lv = length(edgeV);
    if (!(lu > 0) || !Number.isFinite(lu)) fail(CODE, `${f}.edgeU`, 'must be a non-zero finite vector');
    if (!(lv > 0) || !Number.isFinite(lv)) fail(CODE, `${f}.edgeV`, 'must be a non-zero finite vector');
    if (Math.abs(dot(edgeU, edgeV)) > 1e-4 * lu * lv) fail(CODE, `${f}.edgeV`, 'must be orthogonal to edgeU');
    const x = scale(edgeU, 1 / lu);
    const y = scale(edgeV, 1 / lv);
    return { corner: sub(sub(center, scale(edgeU, 0.5)), scale(edgeV, 0.5)), edgeU, edgeV, x, y, z: cross(x, y) };
  });
}

export function validateEnvironmentPortalMode(input: unknown, field = 'environmentPortalMode'): EnvironmentPortalMode {
  if (input === undefined) return 'guide';
  if (input !== 'guide' && input !== 'guide-and-gate') fail(CODE, field, `expected 'guide' or 'guide-and-gate', got ${describe(input)}`);
  return input;
}

/** Probability of sampling through the portals in 'guide' mode (the rest samples the whole map). */
export const PORTAL_GUIDE_PROBABILITY = 0.75;
/** Density floor of the rectified distribution, relative to its mean. */
export const PORTAL_DENSITY_FLOOR = 1e-3;

// ---- rectified parametrisation -------------------------------------------------------------------

/** World direction of rectified (u, v), and d omega / d(u, v) there. */
export function portalUvToDirection(portal: Portal, u: number, v: number): { direction: Vec3; jacobian: number } {
  const alpha = -Math.PI / 2 + u * Math.PI;
  const beta = -Math.PI / 2 + v * Math.PI;
  const w = normalize([Math.tan(alpha), Math.tan(beta), 1]);
  const jacobian = (Math.PI * Math.PI * (1 - w[0] * w[0]) * (1 - w[1] * w[1])) / w[2];
  return { direction: add(add(scale(portal.x, w[0]), scale(portal.y, w[1])), scale(portal.z, w[2])), jacobian };
}

/** Rectified (u, v) of a world direction with a positive component along the outward normal, else null. */
export function portalDirectionToUv(portal: Portal, d: readonly number[]): { u: number; v: number; jacobian: number } | null {
  const w: Vec3 = [dot(d, portal.x), dot(d, portal.y), dot(d, portal.z)];
  if (!(w[2] > 0)) return null;
  const jacobian = (Math.PI * Math.PI * (1 - w[0] * w[0]) * (1 - w[1] * w[1])) / w[2];
  const u = Math.min(1, Math.max(0, (Math.atan2(w[0], w[2]) + Math.PI / 2) / Math.PI));
  const v = Math.min(1, Math.max(0, (Math.atan2(w[1], w[2]) + Math.PI / 2) / Math.PI));
  return { u, v, jacobian };
}

/** The window [u0, u1] x [v0, v1] of directions from `p` through the portal, or null if `p` is not behind it. */
export function portalWindow(portal: Portal, p: readonly number[]): [number, number, number, number] | null {
  if (!(dot(sub(portal.corner, p), portal.z) > 0)) return null;
  const a = portalDirectionToUv(portal, normalize(sub(portal.corner, p)));
  const b = portalDirectionToUv(portal, normalize(sub(add(add(portal.corner, portal.edgeU), portal.edgeV), p)));
  if (!a || !b) return null;
  return [Math.min(a.u, b.u), Math.max(a.u, b.u), Math.min(a.v, b.v), Math.max(a.v, b.v)];
}

// ---- summed-area table and windowed sampling -------------------------------------------------------

/** A piecewise-constant density on [0, 1]^2 (n x n cells) with its summed-area table. */
export interface WindowedDistribution {
  n: number;
  /** Cell values, row-major (v rows). */
  func: Float64Array;
  /** (n + 1)^2 entries: sat[y (n + 1) + x] = integral over [0, x / n] x [0, y / n]. */
  sat: Float64Array;
}

export function buildWindowedDistribution(func: Float64Array, n: number): WindowedDistribution {
  const sat = new Float64Array((n + 1) * (n + 1));
  for (let y = 1; y <= n; y++) {
    let row = 0;
    for (let x = 1; x <= n; x++) {
      row += func[(y - 1) * n + (x - 1)]! / (n * n);
      sat[y * (n + 1) + x] = sat[(y - 1) * (n + 1) + x]! + row;
    }
  }
  return { n, func, sat };
}

/** Integral over [0, u] x [0, v]: bilinear in the SAT, exact for a piecewise-constant density. */
function satLookup(d: WindowedDistribution, u: number, v: number): number {
  const n = d.n;
  const x = Math.min(n, Math.max(0, u * n));
  const y = Math.min(n, Math.max(0, v * n));
  const x0 = Math.min(n - 1, Math.floor(x));
  const y0 = Math.min(n - 1, Math.floor(y));
  const fx = x - x0;
  const fy = y - y0;
  const s = (i: number, j: number): number => d.sat[j * (n + 1) + i]!;
  return (1 - fx) * (1 - fy) * s(x0, y0) + fx * (1 - fy) * s(x0 + 1, y0) + (1 - fx) * fy * s(x0, y0 + 1) + fx * fy * s(x0 + 1, y0 + 1);
}

export function windowIntegral(d: WindowedDistribution, u0: number, u1: number, v0: number, v1: number): number {
  return satLookup(d, u1, v1) - satLookup(d, u0, v1) - satLookup(d, u1, v0) + satLookup(d, u0, v0);
}

/** Inverts a monotone P on [lo, hi] (P(lo) = 0, P(hi) = 1) by bisection down to one cell, then linearly. */
function sampleBisection(P: (x: number) => number, u: number, lo: number, hi: number, n: number): number {
  // Each halving moves one end; stops once [lo, hi] lies in one cell (<= log2(n) + 2 steps).
  while (Math.ceil(n * hi) - Math.floor(n * lo) > 1) {
    const mid = (lo + hi) / 2;
    if (P(mid) > u) hi = mid;
    else lo = mid;
  }
  const pLo = P(lo);
  const pHi = P(hi);
  const t = pHi > pLo ? (u - pLo) / (pHi - pLo) : 0.5;
  return Math.min(hi, Math.max(lo, lo + t * (hi - lo)));
}

function cellValue(d: WindowedDistribution, u: number, v: number): number {
  const i = Math.min(d.n - 1, Math.max(0, Math.floor(u * d.n)));
  const j = Math.min(d.n - 1, Math.max(0, Math.floor(v * d.n)));
  return d.func[j * d.n + i]!;
}

/** Samples (u, v) in the window with density func / window integral; null for an empty window. */
export function sampleWindowed(d: WindowedDistribution, window: readonly number[], u1: number, u2: number): { u: number; v: number; pdf: number } | null {
  const [a0, a1, b0, b1] = window as [number, number, number, number];
  const total = windowIntegral(d, a0, a1, b0, b1);
  if (!(total > 0)) return null;
  const u = sampleBisection((x) => windowIntegral(d, a0, x, b0, b1) / total, u1, a0, a1, d.n);
  // Condition on the cell column that holds u (the density is constant across it).
  let c0 = Math.floor(u * d.n) / d.n;
  let c1 = Math.ceil(u * d.n) / d.n;
  if (c0 === c1) c1 = Math.min(1, c1 + 1 / d.n);
  if (c0 === c1) c0 = c1 - 1 / d.n;
  const column = windowIntegral(d, c0, c1, b0, b1);
  if (!(column > 0)) return null;
  const v = sampleBisection((y) => windowIntegral(d, c0, c1, b0, y) / column, u2, b0, b1, d.n);
  return { u, v, pdf: cellValue(d, u, v) / total };
}

/** Density (over (u, v)) of `sampleWindowed` at (u, v): 0 outside the window. */
export function windowedPdf(d: WindowedDistribution, window: readonly number[], u: number, v: number): number {
  const [a0, a1, b0, b1] = window as [number, number, number, number];
  if (u < a0 || u > a1 || v < b0 || v > b1) return 0;
  const total = windowIntegral(d, a0, a1, b0, b1);
  return total > 0 ? cellValue(d, u, v) / total : 0;
}

// ---- the portal environment sampler -----------------------------------------------------------------

export interface PortalEnvironmentSampler {
  environment: EnvironmentSampler;
  portals: Portal[];
  distributions: WindowedDistribution[];
  mode: EnvironmentPortalMode;
}

/**
 * Resamples the environment into each portal's rectified parametrisation (`resolution`^2 cells, the
 * mean of 2 x 2 bilinear lookups per cell, times the Jacobian at the cell centre) and builds its SAT.
 */
export function buildPortalEnvironmentSampler(
  environment: EnvironmentSampler,
  portals: readonly Portal[],
  options: { mode?: EnvironmentPortalMode; resolution?: number } = {},
): PortalEnvironmentSampler {
  const n = options.resolution ?? 64;
  const distributions = portals.map((portal) => {
    const func = new Float64Array(n * n);
    let sum = 0;
    for (let j = 0; j < n; j++) {
      for (let i = 0; i < n; i++) {
        let l = 0;
        for (let a = 0; a < 2; a++) for (let b = 0; b < 2; b++) l += luminance(environmentRadiance(environment.map, portalUvToDirection(portal, (i + 0.25 + 0.5 * a) / n, (j + 0.25 + 0.5 * b) / n).direction));
        const value = (l / 4) * portalUvToDirection(portal, (i + 0.5) / n, (j + 0.5) / n).jacobian;
        func[j * n + i] = value;
        sum += value;
      }
    }
    const floor = (PORTAL_DENSITY_FLOOR * sum) / (n * n);
    for (let k = 0; k < n * n; k++) func[k] = func[k]! + (floor > 0 ? floor : 1);
    return buildWindowedDistribution(func, n);
  });
  return { environment, portals: [...portals], distributions, mode: options.mode ?? 'guide' };
}

interface PortalWindows {
  windows: ([number, number, number, number] | null)[];
  integrals: number[];
  total: number;
}

function windowsAt(s: PortalEnvironmentSampler, p: readonly number[]): PortalWindows {
  const windows = s.portals.map((portal) => portalWindow(portal, p));
  const integrals = windows.map((w, k) => (w ? Math.max(0, windowIntegral(s.distributions[k]!, w[0], w[1], w[2], w[3])) : 0));
  return { windows, integrals, total: integrals.reduce((a, b) => a + b, 0) };
}

/** Density of the portal strategy alone at direction d from p. */
function portalOnlyPdf(s: PortalEnvironmentSampler, w: PortalWindows, d: readonly number[]): number {
  if (!(w.total > 0)) return 0;
  let pdf = 0;
  s.portals.forEach((portal, k) => {
    const window = w.windows[k];
    if (!window) return;
    const uv = portalDirectionToUv(portal, d);
    if (!uv || !(uv.jacobian > 0)) return;
    const density = windowedPdf(s.distributions[k]!, window, uv.u, uv.v);
    if (density > 0) pdf += ((w.integrals[k]! / w.total) * density) / uv.jacobian;
  });
  return pdf;
}

export interface PortalEnvironmentSample {
  direction: Vec3;
  /** Solid-angle density of the whole strategy (mixture included); 0 = no sample. */
  pdf: number;
  radiance: Vec3;
}

/** Probability of taking the portal branch at p (0 when no portal is in view). */
function portalBranchProbability(s: PortalEnvironmentSampler, w: PortalWindows): number {
  if (!(w.total > 0)) return 0;
  return s.mode === 'guide-and-gate' ? 1 : PORTAL_GUIDE_PROBABILITY;
}

/**
 * Samples an environment direction from `p` with uniform (uSelect, u1, u2): uSelect chooses between
 * the portal and plain branches and then the portal (rescaled, as in alias sampling).
 */
export function samplePortalEnvironment(s: PortalEnvironmentSampler, p: readonly number[], uSelect: number, u1: number, u2: number): PortalEnvironmentSample {
  const w = windowsAt(s, p);
  const pPortal = portalBranchProbability(s, w);
  const none: PortalEnvironmentSample = { direction: [0, 1, 0], pdf: 0, radiance: [0, 0, 0] };
  let direction: Vec3;
  if (uSelect < pPortal) {
    let pick = (uSelect / pPortal) * w.total;
    let k = 0;
    while (k < s.portals.length - 1 && (w.integrals[k] === 0 || pick >= w.integrals[k]!)) {
      pick -= w.integrals[k]!;
      k++;
    }
    const window = w.windows[k];
    if (!window) return none;
    const uv = sampleWindowed(s.distributions[k]!, window, u1, u2);
    if (!uv) return none;
    direction = portalUvToDirection(s.portals[k]!, uv.u, uv.v).direction;
  } else {
    if (s.mode === 'guide-and-gate') return none;
    direction = sampleEnvironment(s.environment, u1, u2).direction;
  }
  const pdf = portalEnvironmentPdf(s, p, direction, w);
  if (!(pdf > 0)) return none;
  return { direction, pdf, radiance: environmentRadiance(s.environment.map, direction) };
}

/** Solid-angle density of `samplePortalEnvironment` from `p` in unit direction `d`. */
export function portalEnvironmentPdf(s: PortalEnvironmentSampler, p: readonly number[], d: readonly number[], precomputed?: PortalWindows): number {
  const w = precomputed ?? windowsAt(s, p);
  const pPortal = portalBranchProbability(s, w);
  const viaPortals = pPortal > 0 ? pPortal * portalOnlyPdf(s, w, d) : 0;
  const plain = s.mode === 'guide-and-gate' ? 0 : (1 - pPortal) * environmentPdf(s.environment, d);
  return viaPortals + plain;
}

// ---- GPU layout ----------------------------------------------------------------------------------------


export function packPortals(s: PortalEnvironmentSampler): { records: ArrayBuffer; data: Float32Array } {
  const records = allocateStructArray(environmentPortalLayout, s.portals.length);
  const view = new DataView(records);
  const total = s.distributions.reduce((a, d) => a + d.func.length + d.sat.length, 0);
  const data = new Float32Array(Math.max(1, total));
  let offset = 0;
  s.portals.forEach((portal, k) => {
    const d = s.distributions[k]!;
    data.set(d.func, offset);
    data.set(d.sat, offset + d.func.length);
    writeStruct(environmentPortalLayout, view, k, {
      corner: portal.corner,
      resolution: d.n,
      edgeU: portal.edgeU,
      funcOffset: offset,
      edgeV: portal.edgeV,
      satOffset: offset + d.func.length,
      normal: portal.z,
    });
    offset += d.func.length + d.sat.length;
  });
  return { records, data };
}
