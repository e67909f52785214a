import type { GpuRendererErrorCode } from '../errors/gpu-renderer-error.ts';
import { describe, fail, isArrayLike, requireFiniteNumber, requireNumberInRange } from '../errors/validate.ts';
import { maxRadiance } from './limits.ts';
import { identityTextureTransform, textureTransformMatrix, type TextureTransformRows } from '../materials/textures/texture-transform.ts';
import type { Vec4Input, WavefrontAlphaMode, WavefrontMaterialInput, WavefrontTextureRefInput } from './types.ts';

/** A validated texture reference: which texture, which uv set, the uv transform, scale/strength. */
export interface NormalizedTextureRef {
  texture: number;
  texCoord: 0 | 1;
  transform: TextureTransformRows;
  /** normalTexture.scale or occlusionTexture.strength (1 otherwise). */
  scale: number;
}

/** A validated glTF metallic-roughness material with every default applied. */
export interface NormalizedMaterial {
  name?: string;
  baseColor: [number, number, number, number];
  /** Emitted radiance, emissiveFactor * emissiveStrength. */
  emission: [number, number, number];
  metallic: number;
  roughness: number;
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

/**
 * KHR material extension inputs with their defaults. The factors are part of the scene format; a
 * material that sets one to anything but its default is refused with a typed error until the BSDF
 * implements that extension, so no scene renders silently as something else.
 */
const extensionDefaults: Readonly<Record<string, number | readonly number[] | undefined>> = {
  specularFactor: 1,
  specularColorFactor: [1, 1, 1],
  transmissionFactor: 0,
  thicknessFactor: 0,
  attenuationColor: [1, 1, 1],
  attenuationDistance: Infinity,
  clearcoatFactor: 0,
  clearcoatRoughnessFactor: 0,
  sheenColorFactor: [0, 0, 0],
  sheenRoughnessFactor: 0,
  dispersion: 0,
  iridescenceFactor: 0,
  iridescenceIor: 1.3,
  iridescenceThicknessMinimum: 100,
  iridescenceThicknessMaximum: 400,
  anisotropyStrength: 0,
  anisotropyRotation: 0,
  diffuseTransmissionFactor: 0,
  diffuseTransmissionColorFactor: [1, 1, 1],
};
const extensionTextures = [
  'specularTexture', 'specularColorTexture', 'transmissionTexture', 'thicknessTexture', 'clearcoatTexture', 'clearcoatRoughnessTexture',
  'clearcoatNormalTexture', 'sheenColorTexture', 'sheenRoughnessTexture', 'iridescenceTexture', 'iridescenceThicknessTexture',
  'anisotropyTexture', 'diffuseTransmissionTexture', 'diffuseTransmissionColorTexture',
] as const;
const coreKeys = new Set([
  'name', 'baseColorFactor', 'baseColorTexture', 'metallicFactor', 'roughnessFactor', 'metallicRoughnessTexture', 'normalTexture',
  'occlusionTexture', 'emissiveFactor', 'emissiveTexture', 'emissiveStrength', 'ior', 'doubleSided', 'alphaMode', 'alphaCutoff',
]);

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

function isDefault(value: unknown, fallback: number | readonly number[] | undefined): boolean {
  if (typeof fallback === 'number') return value === fallback;
  if (!isArrayLike(value) || fallback === undefined || value.length !== fallback.length) return false;
  for (let i = 0; i < fallback.length; i++) if (value[i] !== fallback[i]) return false;
  return true;
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
  const m = input ?? {};
  if (typeof m !== 'object' || m === null || Array.isArray(m)) fail(code, field, `expected a material object, got ${describe(m)}`);
  for (const key of Object.keys(m)) {
    if (coreKeys.has(key)) continue;
    if (key in extensionDefaults) {
      const value = (m as Record<string, unknown>)[key];
      if (value !== undefined && !isDefault(value, extensionDefaults[key])) {
        fail(code, `${field}.${key}`, 'this KHR material extension is not supported by this renderer version; remove it or set its default');
      }
    } else if ((extensionTextures as readonly string[]).includes(key)) {
      if ((m as Record<string, unknown>)[key] !== undefined) fail(code, `${field}.${key}`, 'this KHR material extension texture is not supported by this renderer version');
    } else {
      fail(code, `${field}.${key}`, 'unknown material key');
    }
  }
  const baseColor = color(m.baseColorFactor, `${field}.baseColorFactor`, 4, defaultMaterial.baseColor, code) as NormalizedMaterial['baseColor'];
  if (baseColor[3] > 1) fail(code, `${field}.baseColorFactor[3]`, `alpha must be <= 1, got ${baseColor[3]}`);
  const metallic = m.metallicFactor === undefined ? 1 : requireNumberInRange(m.metallicFactor, `${field}.metallicFactor`, { min: 0, max: 1 }, code);
  const roughness = m.roughnessFactor === undefined ? 1 : requireNumberInRange(m.roughnessFactor, `${field}.roughnessFactor`, { min: 0, max: 1 }, code);
  const ior = m.ior === undefined ? 1.5 : requireNumberInRange(m.ior, `${field}.ior`, { min: 1, max: 10 }, code);
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
  return out;
}

export function isEmissive(material: NormalizedMaterial): boolean {
  return material.emission[0] > 0 || material.emission[1] > 0 || material.emission[2] > 0;
}
