import { allocateStructArray, writeStruct } from '../gpu-layout/struct-layout.ts';
import { LIGHT_FLAG_DOUBLE_SIDED, lightEntryLayout } from '../gpu-layout/records.ts';
import { buildAliasTable } from './alias-table.ts';

/** Rec. 709 luminance, the same weights as `luminance()` in math.wgsl. */
export function luminance(c: readonly number[]): number {
  return 0.2126 * c[0]! + 0.7152 * c[1]! + 0.0722 * c[2]!;
}

export interface EmissiveTriangleInput {
  /** Triangle slot in the (BVH-ordered) triangle buffers. */
  triangle: number;
  v0: readonly number[];
  v1: readonly number[];
  v2: readonly number[];
  /** Triangle area, as the caller computed it for the attribute records. */
  area: number;
  emission: readonly number[];
  doubleSided: boolean;
}

export interface EmissiveLightTable {
  /** Packed LightEntry records (one dummy record when there are no lights). */
  entries: ArrayBuffer;
  count: number;
  /** Selection probability by triangle slot, for MIS at emitter hits. */
  pmfByTriangle: Map<number, number>;
  /** Total emitted power estimate (sum of area * luminance * sides * pi). */
  totalPower: number;
}


/**
 * Emissive triangles chosen in proportion to their power (area x luminance, twice for two-sided
 * emitters) through an alias table. Zero-area or black triangles are never chosen.
 */
export function buildEmissiveLightTable(lights: readonly EmissiveTriangleInput[]): EmissiveLightTable {
  const usable = lights.filter((l) => l.area > 0 && luminance(l.emission) > 0);
  const pmfByTriangle = new Map<number, number>();
  if (usable.length === 0) return { entries: allocateStructArray(lightEntryLayout, 1), count: 0, pmfByTriangle, totalPower: 0 };
  const power = usable.map((l) => l.area * luminance(l.emission) * (l.doubleSided ? 2 : 1) * Math.PI);
  const table = buildAliasTable(power);
  const entries = allocateStructArray(lightEntryLayout, usable.length);
  const view = new DataView(entries);
  usable.forEach((l, i) => {
    const pmf = table.pmf[i]!;
    pmfByTriangle.set(l.triangle, pmf);
    writeStruct(lightEntryLayout, view, i, {
      v0: l.v0,
      e1: [l.v1[0]! - l.v0[0]!, l.v1[1]! - l.v0[1]!, l.v1[2]! - l.v0[2]!],
      e2: [l.v2[0]! - l.v0[0]!, l.v2[1]! - l.v0[1]!, l.v2[2]! - l.v0[2]!],
      threshold: table.threshold[i]!,
      aliasIndex: table.alias[i]!,
      triangle: (l.triangle | (l.doubleSided ? LIGHT_FLAG_DOUBLE_SIDED : 0)) >>> 0,
      emission: l.emission,
      pmf,
    });
  });
  return { entries, count: usable.length, pmfByTriangle, totalPower: power.reduce((a, b) => a + b, 0) };
}
