import { defineStructLayout, type StructLayout } from '../gpu-layout/struct-layout.ts';
import { buildAliasTable } from './alias-table.ts';
import { bilinearTexel, type EnvironmentMap } from './environment-map.ts';
import { directionToEquirectUv, equirectSinTheta, equirectUvToDirection, uvPdfToSolidAngle } from './equirect.ts';
import { luminance, type Vec3 } from './vec3.ts';

/**
 * Importance sampling of an equirectangular environment map in proportion to luminance x sin(theta),
 * following pbrt-v4's ImageInfiniteLight (Pharr, Jakob, Humphreys, 4th ed., sec. 12.5.3): radiance
 * is looked up with bilinear filtering, and the sampling density is piecewise constant per texel,
 * built from the *filtered* image: texel (i, j) weighs the average of the bilinear reconstruction
 * over its own cell (the separable [1/8, 3/4, 1/8] kernel on the 3 x 3 neighbourhood, wrapping in u,
 * clamping in v) times sin(theta) at the row centre. A texel weighs 0 exactly when the filtered
 * radiance is 0 over its whole cell, so every direction with radiance gets a positive density and
 * zero-radiance regions are never sampled.
 *
 * Data structure: alias tables (Walker/Vose, alias-table.ts): a marginal table over rows and one
 * conditional table per row. Chosen over a hierarchical (mip-map) warp because sampling is O(1) with
 * two dependent loads, has no power-of-two restriction, and the renderer draws independent PCG
 * numbers, so the warp's stratification preservation would buy nothing. The alias step leaves a
 * uniform residual of each random number, which places the sample inside its texel: two numbers
 * per sample in all.
 *
 * Table (`entries`, EnvironmentAliasEntry records of 12 bytes; gpu-lighting.ts copies each into an
 * EnvironmentTableEntry cell of the lights heap, read by environment-map.wesl):
 *   records [0, H): marginal over rows: { threshold: f32, alias: u32 (a row), pdf: f32 (the row's pmf) }
 *   records [H + j W, H + (j + 1) W): row j's conditional over columns:
 *     { threshold: f32, alias: u32 (a column of row j), pdf: f32 (pdf_uv of texel (i, j), i = this record's own column) }
 *   where pdf_uv(i, j) = w_ij W H / sum(w) is the density over (u, v) in [0, 1]^2; the solid-angle
 *   density is pdf_uv / (2 pi^2 sin(theta)). Rows that weigh 0 get threshold 1 (never reached).
 * Radiance: the map's RGBA float32 texels (row-major, row 0 = zenith) in an rgba32float texture
 * read with textureLoad and filtered by hand (rgba32float is not filterable without the optional
 * 'float32-filterable' feature; rgba16float would clip HDR suns above 65504).
 * Uniforms: LightingUniforms (map and table sizes, intensity, rotationRadians / (2 pi)).
 */

/** One alias-table bin as the GPU reads it. */
export const environmentAliasEntryLayout: StructLayout = defineStructLayout('EnvironmentAliasEntry', 1, [
  ['threshold', 'f32', 'keep this bin when the scaled residual < threshold, else take alias'],
  ['alias', 'u32', 'marginal: a row index; conditional: a column index within the row'],
  ['pdf', 'f32', 'marginal: the row pmf; conditional: pdf over (u, v) of this texel'],
]);

export interface EnvironmentSampler {
  readonly map: EnvironmentMap;
  /**
   * Size of the sampling tables in cells: the map's size, or coarser for maps above
   * `maxTableCells` (a cell then covers a block of texels; see buildEnvironmentSampler). W and H
   * in the layout above are these.
   */
  readonly tableWidth: number;
  readonly tableHeight: number;
  /** (H + W H) EnvironmentAliasEntry records; see the module comment. */
  readonly entries: ArrayBuffer;
  /** float32 and uint32 views of `entries` (what the GPU reads). */
  readonly entriesF32: Float32Array;
  readonly entriesU32: Uint32Array;
  /** Per-texel sampling weight (filtered luminance x sin theta), row-major. */
  readonly weights: Float64Array;
  /** sum(weights) / (W H): the integral of the weight function over [0, 1]^2. 0: nothing to sample. */
  readonly weightIntegral: number;
}

export interface EnvironmentSample {
  /** Unit direction towards the environment. */
  direction: Vec3;
  /** Solid-angle density; 0 means no sample (black map or a pole). */
  pdf: number;
  /** Radiance from `direction` (bilinear lookup x intensity). */
  radiance: Vec3;
}

/** Largest float32 below 1: keeps a residual inside [0, 1) after rounding. */
export const ONE_MINUS_EPSILON_F32 = 1 - 2 ** -24;

/** Luminance of the bilinear reconstruction averaged over each texel's cell. */
export function filteredTexelLuminance(map: Pick<EnvironmentMap, 'width' | 'height' | 'data'>): Float64Array {
  const { width: w, height: h, data } = map;
  const lum = new Float64Array(w * h);
  for (let t = 0; t < w * h; t++) lum[t] = luminance([data[4 * t]!, data[4 * t + 1]!, data[4 * t + 2]!]);
  // The cell average of a tent-filtered sequence is the [1/8, 3/4, 1/8] kernel (separable).
  const rows = new Float64Array(w * h);
  for (let j = 0; j < h; j++) {
    for (let i = 0; i < w; i++) {
      const l = lum[j * w + ((i - 1 + w) % w)]!;
      const r = lum[j * w + ((i + 1) % w)]!;
      rows[j * w + i] = 0.125 * l + 0.75 * lum[j * w + i]! + 0.125 * r;
    }
  }
  const out = new Float64Array(w * h);
  for (let j = 0; j < h; j++) {
    const up = Math.max(0, j - 1);
    const down = Math.min(h - 1, j + 1);
    for (let i = 0; i < w; i++) out[j * w + i] = 0.125 * rows[up * w + i]! + 0.75 * rows[j * w + i]! + 0.125 * rows[down * w + i]!;
  }
  return out;
}

/** Table size for a map: halved (rounding up) until it has at most `maxCells` cells. */
export function environmentTableSize(width: number, height: number, maxCells = Infinity): [number, number] {
  let w = width;
  let h = height;
  while (w * h > maxCells && (w > 1 || h > 1)) {
    w = Math.ceil(w / 2);
    h = Math.ceil(h / 2);
  }
  return [w, h];
}

/**
 * Builds the tables (`uniform`: sin(theta) weights only, i.e. uniform directions, for measuring
 * what importance sampling gains). With `maxTableCells` below the map's texel count the tables get coarser
 * (environmentTableSize): table cell (I, J) covers texel columns [floor(I W / W_t), floor((I + 1) W
 * / W_t)) and the rows likewise, and weighs the mean filtered luminance of its texels times
 * sin(theta) at its own centre row. Sampling and pdf use the table's cells throughout, so they stay
 * consistent, and a cell weighs 0 only where the radiance is 0 over all of it.
 */
export function buildEnvironmentSampler(map: EnvironmentMap, options: { maxTableCells?: number; uniform?: boolean } = {}): EnvironmentSampler {
  const [w, h] = environmentTableSize(map.width, map.height, options.maxTableCells);
  let cellLuminance: Float64Array;
  if (options.uniform) {
    // Uniform over the sphere (weights sin(theta) only): the baseline importance sampling is measured against.
    cellLuminance = new Float64Array(w * h).fill(1);
  } else {
    const filtered = filteredTexelLuminance(map);
    cellLuminance = w === map.width && h === map.height ? filtered : blockMeans(filtered, map.width, map.height, w, h);
  }
  const weights = new Float64Array(w * h);
  const rowSums = new Float64Array(h);
  let total = 0;
  for (let j = 0; j < h; j++) {
    const sinTheta = Math.sin((Math.PI * (j + 0.5)) / h);
    let s = 0;
    for (let i = 0; i < w; i++) {
      const x = cellLuminance[j * w + i]! * sinTheta;
      weights[j * w + i] = x;
      s += x;
    }
    rowSums[j] = s;
    total += s;
  }
  const entries = new ArrayBuffer((h + w * h) * environmentAliasEntryLayout.size);
  const f32 = new Float32Array(entries);
  const u32 = new Uint32Array(entries);
  const put = (record: number, threshold: number, alias: number, pdf: number): void => {
    f32[3 * record] = threshold;
    u32[3 * record + 1] = alias;
    f32[3 * record + 2] = pdf;
  };
  if (total > 0 && Number.isFinite(total)) {
    const marginal = buildAliasTable(rowSums);
    for (let j = 0; j < h; j++) put(j, marginal.threshold[j]!, marginal.alias[j]!, marginal.pmf[j]!);
    for (let j = 0; j < h; j++) {
      const base = h + j * w;
      if (!(rowSums[j]! > 0)) {
        for (let i = 0; i < w; i++) put(base + i, 1, i, 0);
        continue;
      }
      const row = buildAliasTable(weights.subarray(j * w, (j + 1) * w));
      for (let i = 0; i < w; i++) put(base + i, row.threshold[i]!, row.alias[i]!, (weights[j * w + i]! * w * h) / total);
    }
  } else {
    total = 0;
  }
  return { map, tableWidth: w, tableHeight: h, entries, entriesF32: f32, entriesU32: u32, weights, weightIntegral: total / (w * h) };
}

/** Means of the values over the blocks of texels each coarse cell covers. */
function blockMeans(values: Float64Array, width: number, height: number, w: number, h: number): Float64Array {
  const out = new Float64Array(w * h);
  for (let J = 0; J < h; J++) {
    const y0 = Math.floor((J * height) / h);
    const y1 = Math.floor(((J + 1) * height) / h);
    for (let I = 0; I < w; I++) {
      const x0 = Math.floor((I * width) / w);
      const x1 = Math.floor(((I + 1) * width) / w);
      let sum = 0;
      for (let y = y0; y < y1; y++) for (let x = x0; x < x1; x++) sum += values[y * width + x]!;
      out[J * w + I] = sum / ((y1 - y0) * (x1 - x0));
    }
  }
  return out;
}

/**
 * One alias-table draw over records [base, base + n) from uniform `u`: returns the chosen bin and the
 * residual of `u`, uniform in [0, 1) again (what places the sample inside its texel).
 */
export function sampleAliasRecords(f32: Float32Array, u32: Uint32Array, base: number, n: number, u: number): [number, number] {
  const scaled = u * n;
  const bin = Math.min(Math.floor(scaled), n - 1);
  const frac = Math.min(scaled - bin, ONE_MINUS_EPSILON_F32);
  const threshold = f32[3 * (base + bin)]!;
  if (frac < threshold) return [bin, frac / threshold];
  return [u32[3 * (base + bin) + 1]!, Math.min((frac - threshold) / (1 - threshold), ONE_MINUS_EPSILON_F32)];
}

/** Samples a direction with density proportional to the sampling weights (see module comment). */
export function sampleEnvironment(sampler: EnvironmentSampler, u1: number, u2: number): EnvironmentSample {
  const { map } = sampler;
  if (!(sampler.weightIntegral > 0)) return { direction: [0, 1, 0], pdf: 0, radiance: [0, 0, 0] };
  const { entriesF32: f32, entriesU32: u32, tableWidth: w, tableHeight: h } = sampler;
  const [j, rv] = sampleAliasRecords(f32, u32, 0, h, u1);
  const [i, ru] = sampleAliasRecords(f32, u32, h + j * w, w, u2);
  const pdfUv = f32[3 * (h + j * w + i) + 2]!;
  const u = (i + ru) / w;
  const v = (j + rv) / h;
  const direction = equirectUvToDirection(u, v, map.rotationRadians);
  const pdf = uvPdfToSolidAngle(pdfUv, Math.sin(Math.PI * v));
  const t = bilinearTexel(map, u, v);
  return { direction, pdf, radiance: [t[0] * map.intensity, t[1] * map.intensity, t[2] * map.intensity] };
}

/** Solid-angle density with which `sampleEnvironment` returns unit direction `d`. */
export function environmentPdf(sampler: EnvironmentSampler, d: readonly number[]): number {
  if (!(sampler.weightIntegral > 0)) return 0;
  const { tableWidth: w, tableHeight: h } = sampler;
  const [u, v] = directionToEquirectUv(d, sampler.map.rotationRadians);
  const i = Math.min(Math.floor(u * w), w - 1);
  const j = Math.min(Math.floor(v * h), h - 1);
  const f32 = sampler.entriesF32;
  return uvPdfToSolidAngle(f32[3 * (h + j * w + i) + 2]!, equirectSinTheta(d));
}
