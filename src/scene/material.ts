import { fail, isArrayLike, requireFiniteNumber, requireNumberInRange } from '../errors/validate.ts';
import type { Vec4Input, WavefrontMaterialInput } from './types.ts';

/** A validated glTF metallic-roughness material with every default applied. */
export interface NormalizedMaterial {
  baseColor: [number, number, number, number];
  /** Emitted radiance, emissiveFactor * emissiveStrength. */
  emission: [number, number, number];
  metallic: number;
  roughness: number;
  ior: number;
  doubleSided: boolean;
}

export const defaultMaterial: Readonly<NormalizedMaterial> = Object.freeze<NormalizedMaterial>({
  baseColor: [1, 1, 1, 1],
  emission: [0, 0, 0],
  metallic: 1,
  roughness: 1,
  ior: 1.5,
  doubleSided: false,
});

function color(value: unknown, field: string, length: 3 | 4, fallback: readonly number[]): number[] {
  if (value === undefined) return [...fallback];
  if (!isArrayLike(value) || (value.length !== length && !(length === 4 && value.length === 3))) {
    fail('INVALID_MESH', field, `expected ${length === 4 ? '3 or 4' : '3'} numbers`);
  }
  const out: number[] = [];
  for (let i = 0; i < value.length; i++) {
    out.push(requireNumberInRange(value[i], `${field}[${i}]`, { min: 0 }, 'INVALID_MESH'));
  }
  if (length === 4 && out.length === 3) out.push(1);
  return out;
}

/**
 * Validates glTF material factors (glTF 2.0 section 3.9 defaults) and folds the mirrored package's
 * mesh-level `emission: [r, g, b, strength]` in, which overrides the material's emissive terms.
 */
export function normalizeMaterial(input: WavefrontMaterialInput | undefined, field: string, meshEmission?: Vec4Input): NormalizedMaterial {
  const m = input ?? {};
  if (typeof m !== 'object' || m === null) fail('INVALID_MESH', field, 'expected a material object');
  const baseColor = color(m.baseColorFactor, `${field}.baseColorFactor`, 4, defaultMaterial.baseColor) as NormalizedMaterial['baseColor'];
  const metallic = m.metallicFactor === undefined ? 1 : requireNumberInRange(m.metallicFactor, `${field}.metallicFactor`, { min: 0, max: 1 }, 'INVALID_MESH');
  const roughness = m.roughnessFactor === undefined ? 1 : requireNumberInRange(m.roughnessFactor, `${field}.roughnessFactor`, { min: 0, max: 1 }, 'INVALID_MESH');
  const ior = m.ior === undefined ? 1.5 : requireNumberInRange(m.ior, `${field}.ior`, { min: 1, max: 10 }, 'INVALID_MESH');
  const strength = m.emissiveStrength === undefined ? 1 : requireNumberInRange(m.emissiveStrength, `${field}.emissiveStrength`, { min: 0 }, 'INVALID_MESH');
  let emission = color(m.emissiveFactor, `${field}.emissiveFactor`, 3, [0, 0, 0]).map((c) => c * strength) as NormalizedMaterial['emission'];
  if (meshEmission !== undefined) {
    const e = color(meshEmission, field.replace(/\.material$/, '.emission'), 4, [0, 0, 0, 1]);
    requireFiniteNumber(e[3], `${field.replace(/\.material$/, '.emission')}[3]`, 'INVALID_MESH');
    emission = [e[0]! * e[3]!, e[1]! * e[3]!, e[2]! * e[3]!];
  }
  if (m.doubleSided !== undefined && typeof m.doubleSided !== 'boolean') fail('INVALID_MESH', `${field}.doubleSided`, 'expected a boolean');
  return { baseColor, emission, metallic, roughness, ior, doubleSided: m.doubleSided ?? false };
}

export function isEmissive(material: NormalizedMaterial): boolean {
  return material.emission[0] > 0 || material.emission[1] > 0 || material.emission[2] > 0;
}
