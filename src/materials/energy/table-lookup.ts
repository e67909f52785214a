/**
 * The albedo tables as the GPU reads them: packing into interpolation cells (each vec4 holds the
 * four corners of one bilinear cell, so energy-tables.wesl does one load per bilinear lookup) and
 * the same lookups on the CPU (for the double-precision references of the composed BSDF).
 */
import {
  DIELECTRIC_TABLE_ETA_NODES,
  DIELECTRIC_TABLE_MU_NODES,
  DIELECTRIC_TABLE_ROUGHNESS_NODES,
  ENERGY_TABLE_MU_NODES,
  ENERGY_TABLE_ROUGHNESS_NODES,
  SHEEN_TABLE_NODES,
} from '../../gpu-layout/constants.ts';
import { albedoTable, etaAxis, type AlbedoTables } from './albedo-tables.ts';

/** Corner cells of a rows x cols node table (row-major) starting at `first`: 4 floats per cell. */
function cells2d(values: ArrayLike<number>, first: number, rows: number, cols: number): number[] {
  const out: number[] = [];
  const at = (a: number, b: number): number => values[first + a * cols + b]!;
  for (let a = 0; a + 1 < rows; a++) {
    for (let b = 0; b + 1 < cols; b++) out.push(at(a, b), at(a, b + 1), at(a + 1, b), at(a + 1, b + 1));
  }
  return out;
}

function cells1d(values: ArrayLike<number>, first: number, n: number): number[] {
  const out: number[] = [];
  for (let a = 0; a + 1 < n; a++) out.push(values[first + a]!, values[first + a + 1]!, 0, 0);
  return out;
}

/** A table in the heap's cell form (what packMaterialTables uploads). */
export function packedAlbedoTable(name: keyof AlbedoTables): Float32Array {
  const t = albedoTable(name);
  const out: number[] = [];
  if (name === 'ggx' || name === 'clearcoat') {
    const nr = ENERGY_TABLE_ROUGHNESS_NODES;
    const nm = ENERGY_TABLE_MU_NODES;
    out.push(...cells2d(t, 0, nr, nm));
    if (name === 'ggx') out.push(...cells1d(t, nr * nm, nr));
  } else if (name === 'sheen') {
    out.push(...cells2d(t, 0, SHEEN_TABLE_NODES, SHEEN_TABLE_NODES));
  } else {
    const ne = DIELECTRIC_TABLE_ETA_NODES;
    const nr = DIELECTRIC_TABLE_ROUGHNESS_NODES;
    const nm = DIELECTRIC_TABLE_MU_NODES;
    for (let k = 0; k < ne; k++) out.push(...cells2d(t, k * nr * nm, nr, nm));
    if (name === 'dielectric') out.push(...cells2d(t, ne * nr * nm, ne, nr));
  }
  return Float32Array.from(out);
}

// ---- CPU lookups (the interpolation of energy-tables.wesl, on the f32 node values) ---------------

function axis(t: number, n: number): { i0: number; f: number } {
  const x = Math.min(1, Math.max(0, t)) * (n - 1);
  const i0 = Math.min(Math.floor(x), n - 2);
  return { i0, f: x - i0 };
}

function lerp(a: number, b: number, t: number): number {
  return a + (b - a) * t;
}

function bilinear(values: ArrayLike<number>, first: number, rows: number, cols: number, outer: number, inner: number): number {
  const a = axis(outer, rows);
  const b = axis(inner, cols);
  const at = (i: number, j: number): number => Math.fround(values[first + i * cols + j]!);
  return lerp(lerp(at(a.i0, b.i0), at(a.i0, b.i0 + 1), b.f), lerp(at(a.i0 + 1, b.i0), at(a.i0 + 1, b.i0 + 1), b.f), a.f);
}

/** The dielectric tables' coordinate in [0, 1] of a relative index (Infinity: the ior = 0 mode). */
export function dielectricEtaCoordinate(eta: number): number {
  return 0.5 * (etaAxis(eta) + 1);
}

export function lookupGgxAlbedo(mu: number, r: number): number {
  return bilinear(albedoTable('ggx'), 0, ENERGY_TABLE_ROUGHNESS_NODES, ENERGY_TABLE_MU_NODES, r, mu);
}

export function lookupGgxAlbedoAverage(r: number): number {
  const n = ENERGY_TABLE_ROUGHNESS_NODES;
  const a = axis(r, n);
  const t = albedoTable('ggx');
  const first = n * ENERGY_TABLE_MU_NODES;
  return lerp(Math.fround(t[first + a.i0]!), Math.fround(t[first + a.i0 + 1]!), a.f);
}

function dielectric(name: 'dielectric' | 'dielectricTransmission', mu: number, r: number, y: number): number {
  const nr = DIELECTRIC_TABLE_ROUGHNESS_NODES;
  const nm = DIELECTRIC_TABLE_MU_NODES;
  const a = axis(y, DIELECTRIC_TABLE_ETA_NODES);
  const t = albedoTable(name);
  return lerp(bilinear(t, a.i0 * nr * nm, nr, nm, r, mu), bilinear(t, (a.i0 + 1) * nr * nm, nr, nm, r, mu), a.f);
}

/** y: dielectricEtaCoordinate(eta). */
export function lookupDielectricAlbedo(mu: number, r: number, y: number): number {
  return dielectric('dielectric', mu, r, y);
}

export function lookupDielectricAlbedoAverage(r: number, y: number): number {
  const ne = DIELECTRIC_TABLE_ETA_NODES;
  const nr = DIELECTRIC_TABLE_ROUGHNESS_NODES;
  return bilinear(albedoTable('dielectric'), ne * nr * DIELECTRIC_TABLE_MU_NODES, ne, nr, y, r);
}

export function lookupDielectricInterfaceAlbedo(mu: number, r: number, y: number): number {
  return dielectric('dielectricTransmission', mu, r, y);
}

export function lookupClearcoatAlbedo(mu: number, r: number): number {
  return bilinear(albedoTable('clearcoat'), 0, ENERGY_TABLE_ROUGHNESS_NODES, ENERGY_TABLE_MU_NODES, r, mu);
}

export function lookupSheenAlbedo(mu: number, r: number): number {
  return bilinear(albedoTable('sheen'), 0, SHEEN_TABLE_NODES, SHEEN_TABLE_NODES, r, mu);
}
