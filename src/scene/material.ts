import type { GpuRendererErrorCode } from '../errors/gpu-renderer-error.ts';
import { describe, fail, isArrayLike, requireFiniteNumber, requireNumberInRange } from '../errors/validate.ts';
import { maxRadiance } from './limits.ts';
import { identityTextureTransform, textureTransformMatrix, type TextureTransformRows } from './texture-transform.ts';
import type { Vec4Input, WavefrontAlphaMode, WavefrontMaterialInput, WavefrontTextureRefInput } from './types.ts';

/** A validated texture reference: which texture, which uv set, the uv transform, scale/strength. */
export interface NormalizedTextureRef {
  texture: number;
  texCoord: 0 | 1;
  transform: TextureTransformRows;
  /** normalTexture.scale or occlusionTexture.strength (1 otherwise). */
  scale: number;
}

/** KHR_materials_specular (present when it changes the material). */
export interface NormalizedSpecular {
  factor: number;
  /** Linear RGB; may exceed 1 (the product with the IOR's F0 is clamped to 1). */
  colorFactor: [number, number, number];
  texture?: NormalizedTextureRef;
  colorTexture?: NormalizedTextureRef;
}

/** KHR_materials_transmission (present when transmissionFactor > 0). */
export interface NormalizedTransmission {
  factor: number;
  texture?: NormalizedTextureRef;
}

/** KHR_materials_volume (present when thicknessFactor > 0 and light enters: a refractive solid). */
export interface NormalizedVolume {
  thicknessFactor: number;
  thicknessTexture?: NormalizedTextureRef;
  attenuationColor: [number, number, number];
  /** Infinity: no absorption. */
  attenuationDistance: number;
}

/** KHR_materials_clearcoat (present when clearcoatFactor > 0). */
export interface NormalizedClearcoat {
  factor: number;
  texture?: NormalizedTextureRef;
  roughnessFactor: number;
  roughnessTexture?: NormalizedTextureRef;
  normalTexture?: NormalizedTextureRef;
}

/** KHR_materials_sheen (present when sheenColorFactor is not black). */
export interface NormalizedSheen {
  colorFactor: [number, number, number];
  colorTexture?: NormalizedTextureRef;
  roughnessFactor: number;
  roughnessTexture?: NormalizedTextureRef;
}

/** KHR_materials_iridescence (present when iridescenceFactor > 0). */
export interface NormalizedIridescence {
  factor: number;
  texture?: NormalizedTextureRef;
  ior: number;
  thicknessMinimum: number;
  thicknessMaximum: number;
  thicknessTexture?: NormalizedTextureRef;
}

/** KHR_materials_anisotropy (present when anisotropyStrength > 0). */
export interface NormalizedAnisotropy {
  strength: number;
  /** Radians, counter-clockwise from the tangent. */
  rotation: number;
  texture?: NormalizedTextureRef;
}

/** KHR_materials_diffuse_transmission (present when diffuseTransmissionFactor > 0). */
export interface NormalizedDiffuseTransmission {
  factor: number;
  texture?: NormalizedTextureRef;
  colorFactor: [number, number, number];
  colorTexture?: NormalizedTextureRef;
}

/**
 * A validated glTF metallic-roughness material with every default applied. A KHR extension block
 * is present only when its factors change the material (an extension at its defaults is absent),
 * so consumers can test presence instead of comparing defaults.
 */
export interface NormalizedMaterial {
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
  specular?: NormalizedSpecular;
  transmission?: NormalizedTransmission;
  volume?: NormalizedVolume;
  clearcoat?: NormalizedClearcoat;
  sheen?: NormalizedSheen;
  iridescence?: NormalizedIridescence;
  anisotropy?: NormalizedAnisotropy;
  diffuseTransmission?: NormalizedDiffuseTransmission;
  /** KHR_materials_dispersion (20 / Abbe number), present when > 0 on a refractive solid. */
  dispersion?: number;
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
export const extensionTextureSlots = {
  specularTexture: { srgb: false },
  specularColorTexture: { srgb: true },
  transmissionTexture: { srgb: false },
  thicknessTexture: { srgb: false },
  clearcoatTexture: { srgb: false },
  clearcoatRoughnessTexture: { srgb: false },
  clearcoatNormalTexture: { srgb: false },
  sheenColorTexture: { srgb: true },
  sheenRoughnessTexture: { srgb: false },
  iridescenceTexture: { srgb: false },
  iridescenceThicknessTexture: { srgb: false },
  anisotropyTexture: { srgb: false },
  diffuseTransmissionTexture: { srgb: false },
  diffuseTransmissionColorTexture: { srgb: true },
} as const;

export type ExtensionTextureSlot = keyof typeof extensionTextureSlots;

const extensionFactorKeys = new Set([
  'specularFactor', 'specularColorFactor', 'transmissionFactor', 'thicknessFactor', 'attenuationColor', 'attenuationDistance', 'clearcoatFactor',
  'clearcoatRoughnessFactor', 'sheenColorFactor', 'sheenRoughnessFactor', 'dispersion', 'iridescenceFactor', 'iridescenceIor',
  'iridescenceThicknessMinimum', 'iridescenceThicknessMaximum', 'anisotropyStrength', 'anisotropyRotation', 'diffuseTransmissionFactor',
  'diffuseTransmissionColorFactor',
]);
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
  add('specularTexture', m.specular?.texture, false);
  add('specularColorTexture', m.specular?.colorTexture, true);
  add('transmissionTexture', m.transmission?.texture, false);
  add('thicknessTexture', m.volume?.thicknessTexture, false);
  add('clearcoatTexture', m.clearcoat?.texture, false);
  add('clearcoatRoughnessTexture', m.clearcoat?.roughnessTexture, false);
  add('clearcoatNormalTexture', m.clearcoat?.normalTexture, false);
  add('sheenColorTexture', m.sheen?.colorTexture, true);
  add('sheenRoughnessTexture', m.sheen?.roughnessTexture, false);
  add('iridescenceTexture', m.iridescence?.texture, false);
  add('iridescenceThicknessTexture', m.iridescence?.thicknessTexture, false);
  add('anisotropyTexture', m.anisotropy?.texture, false);
  add('diffuseTransmissionTexture', m.diffuseTransmission?.texture, false);
  add('diffuseTransmissionColorTexture', m.diffuseTransmission?.colorTexture, true);
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
 * mirrored package's mesh-level `emission: [r, g, b, strength]` in, which overrides the material's
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

type Extensions = Pick<NormalizedMaterial, 'specular' | 'transmission' | 'volume' | 'clearcoat' | 'sheen' | 'iridescence' | 'anisotropy' | 'diffuseTransmission' | 'dispersion'>;

/**
 * The KHR material extensions' factors and textures, validated against the ranges of each
 * extension's JSON schema; a block is kept only when it changes the material.
 */
function normalizeExtensions(m: WavefrontMaterialInput, field: string, textureCount: number, code: GpuRendererErrorCode): Extensions {
  const at = (key: string): string => `${field}.${key}`;
  const unit = (key: keyof WavefrontMaterialInput, fallback: number): number => {
    const v = m[key];
    return v === undefined ? fallback : requireNumberInRange(v, at(key), { min: 0, max: 1 }, code);
  };
  const nonNegative = (key: keyof WavefrontMaterialInput, fallback: number): number => {
    const v = m[key];
    return v === undefined ? fallback : requireNumberInRange(v, at(key), { min: 0 }, code);
  };
  const rgb = (key: keyof WavefrontMaterialInput, fallback: readonly number[], max?: number): [number, number, number] => {
    const c = color(m[key], at(key), 3, fallback, code) as [number, number, number];
    if (max !== undefined) c.forEach((v, i) => { if (v > max) fail(code, `${at(key)}[${i}]`, `must be <= ${max}, got ${v}`); });
    return c;
  };
  const texture = (key: ExtensionTextureSlot): NormalizedTextureRef | undefined => {
    const ref = m[key];
    return ref === undefined ? undefined : normalizeTextureRef(ref, at(key), textureCount, code);
  };
  const withTextures = <T extends object>(block: T, textures: Record<string, NormalizedTextureRef | undefined>): T => {
    for (const [k, v] of Object.entries(textures)) if (v !== undefined) (block as Record<string, unknown>)[k] = v;
    return block;
  };
  const out: Extensions = {};

  // KHR_materials_specular: specularFactor in [0, 1], specularColorFactor >= 0 (may exceed 1).
  const specular = unit('specularFactor', 1);
  const specularColor = rgb('specularColorFactor', [1, 1, 1]);
  const specularTextures = { texture: texture('specularTexture'), colorTexture: texture('specularColorTexture') };
  if (specular !== 1 || specularColor.some((c) => c !== 1) || specularTextures.texture || specularTextures.colorTexture) {
    out.specular = withTextures<NormalizedSpecular>({ factor: specular, colorFactor: specularColor }, specularTextures);
  }
  // KHR_materials_transmission and KHR_materials_diffuse_transmission: fractions in [0, 1].
  const transmission = unit('transmissionFactor', 0);
  const transmissionTexture = texture('transmissionTexture');
  if (transmission > 0) out.transmission = withTextures<NormalizedTransmission>({ factor: transmission }, { texture: transmissionTexture });
  const diffuseTransmission = unit('diffuseTransmissionFactor', 0);
  const diffuseTransmissionColor = rgb('diffuseTransmissionColorFactor', [1, 1, 1], 1);
  const diffuseTextures = { texture: texture('diffuseTransmissionTexture'), colorTexture: texture('diffuseTransmissionColorTexture') };
  if (diffuseTransmission > 0) {
    out.diffuseTransmission = withTextures<NormalizedDiffuseTransmission>({ factor: diffuseTransmission, colorFactor: diffuseTransmissionColor }, diffuseTextures);
  }
  // KHR_materials_volume: thicknessFactor >= 0, attenuationDistance > 0 (Infinity: none),
  // attenuationColor in [0, 1]. Only a solid that light can enter is a volume.
  const thickness = nonNegative('thicknessFactor', 0);
  const thicknessTexture = texture('thicknessTexture');
  const attenuationColor = rgb('attenuationColor', [1, 1, 1], 1);
  let attenuationDistance = Infinity;
  if (m.attenuationDistance !== undefined && m.attenuationDistance !== Infinity) {
    attenuationDistance = requireNumberInRange(m.attenuationDistance, at('attenuationDistance'), { min: 0 }, code);
    if (attenuationDistance === 0) fail(code, at('attenuationDistance'), 'must be > 0 (Infinity: no absorption)');
  }
  if (thickness > 0 && (out.transmission || out.diffuseTransmission)) {
    out.volume = withTextures<NormalizedVolume>({ thicknessFactor: thickness, attenuationColor, attenuationDistance }, { thicknessTexture });
  }
  // KHR_materials_dispersion: >= 0; it bends light only inside a refractive solid.
  const dispersion = nonNegative('dispersion', 0);
  if (dispersion > 0 && out.volume) out.dispersion = dispersion;
  // KHR_materials_clearcoat: factor and roughness in [0, 1].
  const clearcoat = unit('clearcoatFactor', 0);
  const clearcoatRoughness = unit('clearcoatRoughnessFactor', 0);
  const clearcoatTextures = { texture: texture('clearcoatTexture'), roughnessTexture: texture('clearcoatRoughnessTexture'), normalTexture: texture('clearcoatNormalTexture') };
  if (clearcoat > 0) out.clearcoat = withTextures<NormalizedClearcoat>({ factor: clearcoat, roughnessFactor: clearcoatRoughness }, clearcoatTextures);
  // KHR_materials_sheen: colour in [0, 1], roughness in [0, 1].
  const sheenColor = rgb('sheenColorFactor', [0, 0, 0], 1);
  const sheenRoughness = unit('sheenRoughnessFactor', 0);
  const sheenTextures = { colorTexture: texture('sheenColorTexture'), roughnessTexture: texture('sheenRoughnessTexture') };
  if (sheenColor.some((c) => c > 0)) out.sheen = withTextures<NormalizedSheen>({ colorFactor: sheenColor, roughnessFactor: sheenRoughness }, sheenTextures);
  // KHR_materials_iridescence: factor in [0, 1], film ior >= 1, thicknesses >= 0 nm (either order).
  const iridescence = unit('iridescenceFactor', 0);
  const iridescenceIor = m.iridescenceIor === undefined ? 1.3 : requireNumberInRange(m.iridescenceIor, at('iridescenceIor'), { min: 1 }, code);
  const thicknessMinimum = nonNegative('iridescenceThicknessMinimum', 100);
  const thicknessMaximum = nonNegative('iridescenceThicknessMaximum', 400);
  const iridescenceTextures = { texture: texture('iridescenceTexture'), thicknessTexture: texture('iridescenceThicknessTexture') };
  if (iridescence > 0) {
    out.iridescence = withTextures<NormalizedIridescence>({ factor: iridescence, ior: iridescenceIor, thicknessMinimum, thicknessMaximum }, iridescenceTextures);
  }
  // KHR_materials_anisotropy: strength in [0, 1], rotation any angle.
  const anisotropy = unit('anisotropyStrength', 0);
  const rotation = m.anisotropyRotation === undefined ? 0 : requireFiniteNumber(m.anisotropyRotation, at('anisotropyRotation'), code);
  const anisotropyTexture = texture('anisotropyTexture');
  if (anisotropy > 0) out.anisotropy = withTextures<NormalizedAnisotropy>({ strength: anisotropy, rotation }, { texture: anisotropyTexture });
  return out;
}

export function isEmissive(material: NormalizedMaterial): boolean {
  return material.emission[0] > 0 || material.emission[1] > 0 || material.emission[2] > 0;
}
