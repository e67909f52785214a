/**
 * Raster materials: the glTF core material (validated by the shared `normalizeMaterial`) plus the
 * KHR extension factors and textures the raster renderer shades as the Khronos sample viewer does:
 * ior and the registry extensions marked `raster: 'drawn'` (specular, clearcoat, sheen,
 * transmission, volume attenuation). The others (`raster: 'refused'`: iridescence, anisotropy,
 * dispersion, diffuse transmission, and any new extension until the raster renderer draws it) are
 * refused with INVALID_MATERIAL when set to anything but their defaults, never drawn as something
 * else.
 */
import { describe, fail, isArrayLike, requireNumberInRange } from '../../errors/validate.ts';
import { anyMaterialExtensions } from '../../materials/extensions/index.ts';
import { normalizeMaterial, normalizeTextureRef, type NormalizedMaterial, type NormalizedTextureRef } from '../../scene/material.ts';
import type { WavefrontMaterialInput } from '../../scene/types.ts';
import { rasterTextureSlots, type RasterTextureSlot } from '../gpu/raster-layout.ts';

export interface RasterMaterial {
  readonly core: NormalizedMaterial;
  readonly specular: number;
  readonly specularColor: [number, number, number];
  readonly clearcoat: number;
  readonly clearcoatRoughness: number;
  readonly sheenColor: [number, number, number];
  readonly sheenRoughness: number;
  readonly transmission: number;
  readonly thickness: number;
  readonly attenuationColor: [number, number, number];
  /** Infinity: no absorption. */
  readonly attenuationDistance: number;
  /** Texture reference of every bound slot. */
  readonly textures: Partial<Record<RasterTextureSlot, NormalizedTextureRef>>;
}

const drawnExtensions = anyMaterialExtensions.filter((e) => e.raster === 'drawn');
const refusedExtensions = anyMaterialExtensions.filter((e) => e.raster === 'refused');
const drawnFactors = new Set(drawnExtensions.flatMap((e) => e.factors.map((f) => f.key)));
const drawnTextures = new Set<string>(rasterTextureSlots.map((s) => s.name).filter((n) => !['baseColorTexture', 'metallicRoughnessTexture', 'normalTexture', 'occlusionTexture', 'emissiveTexture'].includes(n)));
/**
 * Textures of drawn extensions without a raster slot (volume thickness textures only modulate the
 * slab length; the raster renderer uses the factor).
 */
const ignoredTextures = new Set<string>(drawnExtensions.flatMap((e) => e.textures.map((t) => t.key)).filter((k) => !drawnTextures.has(k)));

function unit(value: unknown, field: string, fallback: number): number {
  return value === undefined ? fallback : requireNumberInRange(value, field, { min: 0, max: 1 }, 'INVALID_MATERIAL');
}

function rgb(value: unknown, field: string, fallback: [number, number, number], max = Infinity): [number, number, number] {
  if (value === undefined) return fallback;
  if (!isArrayLike(value) || value.length !== 3) fail('INVALID_MATERIAL', field, `expected 3 numbers, got ${describe(value)}`);
  return [0, 1, 2].map((i) => requireNumberInRange(value[i], `${field}[${i}]`, { min: 0, max }, 'INVALID_MATERIAL')) as [number, number, number];
}

/** Validates one material for the raster renderer; errors are INVALID_MATERIAL naming `field`. */
export function normalizeRasterMaterial(input: WavefrontMaterialInput | undefined, field: string, textureCount: number): RasterMaterial {
  const m = (input === undefined ? {} : input) as Record<string, unknown>;
  if (typeof m !== 'object' || m === null || Array.isArray(m)) fail('INVALID_MATERIAL', field, `expected a material object, got ${describe(m)}`);
  const coreInput: Record<string, unknown> = {};
  for (const [key, value] of Object.entries(m)) {
    if (!drawnFactors.has(key) && !drawnTextures.has(key) && !ignoredTextures.has(key)) coreInput[key] = value;
  }
  const core = normalizeMaterial(coreInput as WavefrontMaterialInput, field, { textureCount });
  // Extensions the path tracer renders but this renderer does not draw: refused, never approximated
  // by something else (the factor that turns each on is named).
  for (const e of refusedExtensions) {
    const key = e.enabledBy;
    if ((core as unknown as Record<string, unknown>)[e.key] !== undefined) fail('INVALID_MATERIAL', `${field}.${key}`, 'the raster renderer does not draw this extension (the path tracer renders it); remove it for the raster view');
  }
  const textures: RasterMaterial['textures'] = {};
  for (const slot of rasterTextureSlots) {
    const ref = slot.name in core ? (core as unknown as Record<string, NormalizedTextureRef | undefined>)[slot.name] : undefined;
    if (ref !== undefined) textures[slot.name] = ref;
    else if (m[slot.name] !== undefined) textures[slot.name] = normalizeTextureRef(m[slot.name] as never, `${field}.${slot.name}`, textureCount);
  }
  const attenuationDistance = m.attenuationDistance === undefined ? Infinity : requireNumberInRange(m.attenuationDistance, `${field}.attenuationDistance`, { min: 0 }, 'INVALID_MATERIAL');
  if (!(attenuationDistance > 0)) fail('INVALID_MATERIAL', `${field}.attenuationDistance`, 'must be > 0');
  return {
    core,
    specular: unit(m.specularFactor, `${field}.specularFactor`, 1),
    specularColor: rgb(m.specularColorFactor, `${field}.specularColorFactor`, [1, 1, 1]),
    clearcoat: unit(m.clearcoatFactor, `${field}.clearcoatFactor`, 0),
    clearcoatRoughness: unit(m.clearcoatRoughnessFactor, `${field}.clearcoatRoughnessFactor`, 0),
    sheenColor: rgb(m.sheenColorFactor, `${field}.sheenColorFactor`, [0, 0, 0], 1),
    sheenRoughness: unit(m.sheenRoughnessFactor, `${field}.sheenRoughnessFactor`, 0),
    transmission: unit(m.transmissionFactor, `${field}.transmissionFactor`, 0),
    thickness: m.thicknessFactor === undefined ? 0 : requireNumberInRange(m.thicknessFactor, `${field}.thicknessFactor`, { min: 0 }, 'INVALID_MATERIAL'),
    attenuationColor: rgb(m.attenuationColor, `${field}.attenuationColor`, [1, 1, 1], 1),
    attenuationDistance,
    textures,
  };
}

/** The core-only copy of a material (extension keys the raster renderer draws removed). */
export function coreMaterialInput(input: WavefrontMaterialInput): WavefrontMaterialInput {
  const out: Record<string, unknown> = {};
  for (const [key, value] of Object.entries(input)) if (!drawnFactors.has(key) && !drawnTextures.has(key) && !ignoredTextures.has(key)) out[key] = value;
  return out as WavefrontMaterialInput;
}
