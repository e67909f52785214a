import type { GpuRendererErrorCode } from '../errors/gpu-renderer-error.ts';
import type { NormalizedTextureRef } from './texture-refs.ts';
export type { NormalizedTextureRef };
import { describe, fail, isArrayLike, requireFiniteNumber, requireNumberInRange } from '../errors/validate.ts';
import { maxRadiance } from './limits.ts';
import { identityTextureTransform, textureTransformMatrix } from './texture-transform.ts';
import type { Vec4Input, WavefrontAlphaMode, WavefrontMaterialInput, WavefrontTextureRefInput } from './types.ts';
import {
  anyMaterialExtensions,
  type anisotropy,
  type clearcoat,
  type diffuseTransmission,
  type FactorSpec,
  type iridescence,
  type NormalizedExtension,
  type NormalizedMaterialExtensions,
  type sheen,
  type specular,
  type transmission,
  type volume,
} from '../materials/extensions/index.ts';


// The KHR extension blocks follow from their registry entries (materials/extensions/<name>/extension.ts).
export type NormalizedSpecular = NormalizedExtension<typeof specular>;
export type NormalizedTransmission = NormalizedExtension<typeof transmission>;
/** Present when thicknessFactor > 0 and light enters: a refractive solid. attenuationDistance Infinity: no absorption. */
export type NormalizedVolume = NormalizedExtension<typeof volume>;
export type NormalizedClearcoat = NormalizedExtension<typeof clearcoat>;
export type NormalizedSheen = NormalizedExtension<typeof sheen>;
export type NormalizedIridescence = NormalizedExtension<typeof iridescence>;
/** rotation: radians, counter-clockwise from the tangent. */
export type NormalizedAnisotropy = NormalizedExtension<typeof anisotropy>;
export type NormalizedDiffuseTransmission = NormalizedExtension<typeof diffuseTransmission>;

/**
 * A validated glTF metallic-roughness material with every default applied. A KHR extension block
 * (one key per registry entry: specular, transmission, volume, clearcoat, sheen, iridescence,
 * anisotropy, diffuseTransmission, dispersion) is present only when its factors change the material
 * (an extension at its defaults is absent), so consumers can test presence instead of comparing
 * defaults.
 */
export interface NormalizedMaterial extends NormalizedMaterialExtensions {
  name?: string;
  baseColor: [number, number, number, number];
  /** Emitted radiance, emissiveFactor * emissiveStrength. */
  emission: [number, number, number];
  metallic: number;
  roughness: number;
  /** KHR_materials_ior: >= 1, or 0 for the specular-glossiness compatibility mode (Fresnel = 1). */
  ior: number;
  doubleSided: boolean;
  alphaMode: WavefrontAlphaMode;
  alphaCutoff: number;
  baseColorTexture?: NormalizedTextureRef;
  metallicRoughnessTexture?: NormalizedTextureRef;
  normalTexture?: NormalizedTextureRef;
  occlusionTexture?: NormalizedTextureRef;
  emissiveTexture?: NormalizedTextureRef;
}

export const defaultMaterial: Readonly<NormalizedMaterial> = Object.freeze<NormalizedMaterial>({
  baseColor: [1, 1, 1, 1],
  emission: [0, 0, 0],
  metallic: 1,
  roughness: 1,
  ior: 1.5,
  doubleSided: false,
  alphaMode: 'OPAQUE',
  alphaCutoff: 0.5,
});

/** The texture slots of the core material and whether their colour data is sRGB (glTF 2.0 section 3.9). */
export const coreTextureSlots = {
  baseColorTexture: { srgb: true },
  metallicRoughnessTexture: { srgb: false },
  normalTexture: { srgb: false },
  occlusionTexture: { srgb: false },
  emissiveTexture: { srgb: true },
} as const;

export type CoreTextureSlot = keyof typeof coreTextureSlots;

/** The KHR extension texture slots (input names) and whether their RGB is sRGB colour (each extension's specification). */
export const extensionTextureSlots: Readonly<Record<string, { srgb: boolean }>> = Object.fromEntries(
  anyMaterialExtensions.flatMap((e) => e.textures.map((t) => [t.key, { srgb: t.srgb }])),
);

const extensionFactorKeys = new Set(anyMaterialExtensions.flatMap((e) => e.factors.map((f) => f.key)));
const coreKeys = new Set([
  'name', 'baseColorFactor', 'baseColorTexture', 'metallicFactor', 'roughnessFactor', 'metallicRoughnessTexture', 'normalTexture',
  'occlusionTexture', 'emissiveFactor', 'emissiveTexture', 'emissiveStrength', 'ior', 'doubleSided', 'alphaMode', 'alphaCutoff',
]);

/**
 * Every normalized texture reference of a material (core and extension slots, occlusion included)
 * with the colour space its slot reads it in.
 */
export function materialTextureRefs(m: NormalizedMaterial): { slot: string; ref: NormalizedTextureRef; srgb: boolean }[] {
  const out: { slot: string; ref: NormalizedTextureRef; srgb: boolean }[] = [];
  const add = (slot: string, ref: NormalizedTextureRef | undefined, srgb: boolean): void => {
    if (ref) out.push({ slot, ref, srgb });
  };
  for (const slot of Object.keys(coreTextureSlots) as CoreTextureSlot[]) add(slot, m[slot], coreTextureSlots[slot].srgb);
  for (const e of anyMaterialExtensions) {
    const block = (m as unknown as Record<string, unknown>)[e.key] as Record<string, NormalizedTextureRef | undefined> | undefined;
    for (const t of e.textures) add(t.key, block?.[t.field], t.srgb);
  }
  return out;
}

function color(value: unknown, field: string, length: 3 | 4, fallback: readonly number[], code: GpuRendererErrorCode): number[] {
  if (value === undefined) return [...fallback];
  if (!isArrayLike(value) || (value.length !== length && !(length === 4 && value.length === 3))) {
    fail(code, field, `expected ${length === 4 ? '3 or 4' : '3'} numbers, got ${describe(value)}`);
  }
  const out: number[] = [];
  for (let i = 0; i < value.length; i++) out.push(requireNumberInRange(value[i], `${field}[${i}]`, { min: 0 }, code));
  if (length === 4 && out.length === 3) out.push(1);
  return out;
}

function vec2(value: unknown, field: string, fallback: readonly [number, number], code: GpuRendererErrorCode): [number, number] {
  if (value === undefined) return [...fallback];
  if (!isArrayLike(value) || value.length !== 2) fail(code, field, `expected 2 numbers, got ${describe(value)}`);
  return [requireFiniteNumber(value[0], `${field}[0]`, code), requireFiniteNumber(value[1], `${field}[1]`, code)];
}

/** Validates a texture reference; `textureCount` is the length of the scene's `textures`. */
export function normalizeTextureRef(input: WavefrontTextureRefInput, field: string, textureCount: number, code: GpuRendererErrorCode = 'INVALID_MATERIAL'): NormalizedTextureRef {
  if (typeof input !== 'object' || input === null) fail(code, field, `expected { index, texCoord?, transform?, scale? }, got ${describe(input)}`);
  for (const key of Object.keys(input)) {
    if (!['index', 'texCoord', 'transform', 'scale', 'strength'].includes(key)) fail(code, `${field}.${key}`, 'unknown key');
  }
  const index = input.index;
  if (typeof index !== 'number' || !Number.isInteger(index) || index < 0 || index >= textureCount) {
    fail(code, `${field}.index`, `texture index ${describe(index)} is out of range for ${textureCount} textures`);
  }
  const t = input.transform;
  let texCoord = input.texCoord ?? 0;
  let transform = identityTextureTransform();
  if (t !== undefined) {
    if (typeof t !== 'object' || t === null) fail(code, `${field}.transform`, 'expected { offset?, rotation?, scale?, texCoord? }');
    const rotation = t.rotation === undefined ? 0 : requireFiniteNumber(t.rotation, `${field}.transform.rotation`, code);
    transform = textureTransformMatrix({ offset: vec2(t.offset, `${field}.transform.offset`, [0, 0], code), rotation, scale: vec2(t.scale, `${field}.transform.scale`, [1, 1], code) });
    if (t.texCoord !== undefined) texCoord = t.texCoord;
  }
  if (texCoord !== 0 && texCoord !== 1) fail(code, `${field}.texCoord`, `uv set ${describe(texCoord)} is not supported (0 or 1)`);
  const scaleValue = input.scale ?? input.strength;
  const scale = scaleValue === undefined ? 1 : requireFiniteNumber(scaleValue, `${field}.${input.scale !== undefined ? 'scale' : 'strength'}`, code);
  return { texture: index, texCoord, transform, scale };
}

/**
 * Validates glTF material factors and textures (glTF 2.0 section 3.9 defaults) and folds the
 * mesh-level `emission: [r, g, b, strength]` of the 0.2 API (which hosts written for it still pass) in, which overrides the material's
 * emissive terms. Errors name the field (`materials[2].roughnessFactor`).
 */
export function normalizeMaterial(
  input: WavefrontMaterialInput | undefined,
  field: string,
  options: { textureCount?: number; meshEmission?: Vec4Input; emissionField?: string; code?: GpuRendererErrorCode } = {},
): NormalizedMaterial {
  const code = options.code ?? 'INVALID_MATERIAL';
  const textureCount = options.textureCount ?? 0;
  const meshEmission = options.meshEmission;
  // Only undefined means "the default material": null is a fault like any other non-object.
  const m = input === undefined ? {} : input;
  if (typeof m !== 'object' || m === null || Array.isArray(m)) fail(code, field, `expected a material object, got ${describe(m)}`);
  for (const key of Object.keys(m)) {
    if (!coreKeys.has(key) && !extensionFactorKeys.has(key) && !(key in extensionTextureSlots)) fail(code, `${field}.${key}`, 'unknown material key');
  }
  const baseColor = color(m.baseColorFactor, `${field}.baseColorFactor`, 4, defaultMaterial.baseColor, code) as NormalizedMaterial['baseColor'];
  // glTF 2.0 section 5.22.1: each component in [0, 1] (a reflectance above 1 would create energy).
  baseColor.forEach((c, i) => {
    if (c > 1) fail(code, `${field}.baseColorFactor[${i}]`, `${i === 3 ? 'alpha' : 'reflectance'} must be <= 1, got ${c}`);
  });
  const metallic = m.metallicFactor === undefined ? 1 : requireNumberInRange(m.metallicFactor, `${field}.metallicFactor`, { min: 0, max: 1 }, code);
  const roughness = m.roughnessFactor === undefined ? 1 : requireNumberInRange(m.roughnessFactor, `${field}.roughnessFactor`, { min: 0, max: 1 }, code);
  const ior = m.ior === undefined ? 1.5 : requireNumberInRange(m.ior, `${field}.ior`, { min: 0 }, code);
  // KHR_materials_ior: ior >= 1, or exactly 0 (the specular-glossiness compatibility mode).
  if (ior > 0 && ior < 1) fail(code, `${field}.ior`, `must be >= 1 (or 0 for the specular-glossiness mode), got ${ior}`);
  const strength = m.emissiveStrength === undefined ? 1 : requireNumberInRange(m.emissiveStrength, `${field}.emissiveStrength`, { min: 0 }, code);
  let emission = color(m.emissiveFactor, `${field}.emissiveFactor`, 3, [0, 0, 0], code).map((c) => c * strength) as NormalizedMaterial['emission'];
  let emissionFrom = `${field}.emissiveFactor`;
  if (meshEmission !== undefined) {
    emissionFrom = options.emissionField ?? `${field}.emission`;
    const e = color(meshEmission, emissionFrom, 4, [0, 0, 0, 1], code);
    emission = [e[0]! * e[3]!, e[1]! * e[3]!, e[2]! * e[3]!];
  }
  // Finite factors whose product overflows would reach the light table as infinite power and the
  // film as Inf.
  emission.forEach((c, i) => {
    if (!(c <= maxRadiance)) fail(code, emissionFrom, `emitted radiance ${c} in channel ${i} exceeds the supported maximum ${maxRadiance}`);
  });
  if (m.doubleSided !== undefined && typeof m.doubleSided !== 'boolean') fail(code, `${field}.doubleSided`, `expected a boolean, got ${describe(m.doubleSided)}`);
  const alphaMode = m.alphaMode ?? 'OPAQUE';
  if (alphaMode !== 'OPAQUE' && alphaMode !== 'MASK' && alphaMode !== 'BLEND') fail(code, `${field}.alphaMode`, `expected OPAQUE, MASK or BLEND, got ${describe(alphaMode)}`);
  const alphaCutoff = m.alphaCutoff === undefined ? 0.5 : requireNumberInRange(m.alphaCutoff, `${field}.alphaCutoff`, { min: 0 }, code);
  const out: NormalizedMaterial = { baseColor, emission, metallic, roughness, ior, doubleSided: m.doubleSided ?? false, alphaMode, alphaCutoff };
  if (m.name !== undefined) {
    if (typeof m.name !== 'string') fail(code, `${field}.name`, 'expected a string');
    out.name = m.name;
  }
  for (const slot of Object.keys(coreTextureSlots) as CoreTextureSlot[]) {
    const ref = m[slot];
    if (ref !== undefined) out[slot] = normalizeTextureRef(ref, `${field}.${slot}`, textureCount, code);
  }
  Object.assign(out, normalizeExtensions(m, field, textureCount, code));
  return out;
}

/**
 * The KHR material extensions' factors and textures, validated against the ranges of each
 * extension's JSON schema (its registry entry); a block is kept only when it changes the material.
 */
function normalizeExtensions(m: WavefrontMaterialInput, field: string, textureCount: number, code: GpuRendererErrorCode): NormalizedMaterialExtensions {
  const input = m as Record<string, unknown>;
  const out: Record<string, unknown> = {};
  for (const e of anyMaterialExtensions) {
    const block: Record<string, unknown> = {};
    for (const f of e.factors) block[f.field] = normalizeFactor(f, input[f.key], `${field}.${f.key}`, code);
    for (const t of e.textures) {
      const ref = input[t.key];
      if (ref !== undefined) block[t.field] = normalizeTextureRef(ref as WavefrontTextureRefInput, `${field}.${t.key}`, textureCount, code);
    }
    const value = e.normalized === 'scalar' ? block[e.factors[0]!.field] : block;
    if (e.present(value as never, out)) out[e.key] = value;
  }
  return out as NormalizedMaterialExtensions;
}

/** One extension factor: its default when absent, else checked against the schema range. */
function normalizeFactor(f: FactorSpec, value: unknown, at: string, code: GpuRendererErrorCode): number | [number, number, number] {
  const { min, max, above } = f.range;
  const lower = min ?? above;
  if (f.type === 'rgb') {
    const c = color(value, at, 3, f.default as readonly number[], code) as [number, number, number];
    c.forEach((v, i) => {
      if (max !== undefined && v > max) fail(code, `${at}[${i}]`, `must be <= ${max}, got ${v}`);
    });
    return c;
  }
  if (value === undefined || (f.infinity === true && value === Infinity)) return f.default as number;
  const v = lower === undefined && max === undefined ? requireFiniteNumber(value, at, code) : requireNumberInRange(value, at, { min: lower, max }, code);
  if (above !== undefined && v <= above) fail(code, at, `must be > ${above}${f.infinity ? ' (Infinity: none)' : ''}`);
  return v;
}

export function isEmissive(material: NormalizedMaterial): boolean {
  return material.emission[0] > 0 || material.emission[1] > 0 || material.emission[2] > 0;
}
