import { GpuRendererError } from '../../errors/gpu-renderer-error.ts';
import {
  INDEX_NONE,
  MATERIAL_ALPHA_MODE_SHIFT,
  MATERIAL_FLAG_DOUBLE_SIDED,
  MATERIAL_FLAG_ENERGY_COMPENSATION,
  MATERIAL_FLAG_IOR_INFINITE,
  MATERIAL_TABLES_OFFSET,
  MAX_MEDIA,
  ALPHA_MODE_BLEND,
  ALPHA_MODE_MASK,
  ALPHA_MODE_OPAQUE,
  TEXTURE_BINDING_FLAG_SRGB,
} from '../../gpu-layout/constants.ts';
import { materialCoreLayout, materialTablesLayout, mediumRecordLayout, textureBindingLayout } from '../../gpu-layout/records.ts';
import { absorptionCoefficient, anyMaterialExtensions, type MaterialExtensionKey, type MaterialExtensionSpec, type PackContext } from '../../materials/extensions/index.ts';
import { defineStructLayout, type StructLayout } from '../../gpu-layout/struct-layout.ts';
import type { Vec4Heap } from '../../gpu-layout/vec4-heap.ts';
import type { AlbedoTables } from '../../materials/energy/albedo-tables.ts';
import { packedAlbedoTable } from '../../materials/energy/table-lookup.ts';
import { spectralResponseTable } from '../../materials/extensions/dispersion/spectral-response.ts';
import { materialTextureRefs, type NormalizedMaterial, type NormalizedTextureRef } from '../../scene/material.ts';

/** Heap offset of the TextureInfo of texture `texture` decoded as sRGB or linear data. */
export type TextureInfoOffsets = (texture: number, srgb: boolean) => number;

/** Every (texture, colour space) pair the materials sample: what the atlas must hold. */
export function textureUsages(materials: readonly NormalizedMaterial[]): { texture: number; srgb: boolean }[] {
  const seen = new Map<string, { texture: number; srgb: boolean }>();
  for (const m of materials) {
    for (const { slot, ref, srgb } of materialTextureRefs(m)) {
      if (slot !== 'occlusionTexture') seen.set(`${ref.texture}:${srgb}`, { texture: ref.texture, srgb });
    }
  }
  return [...seen.values()];
}

/** Which KHR material features a scene's materials use (each is a shader feature flag). */
export type MaterialFeatureUses = Record<MaterialExtensionKey | 'energyCompensation', boolean>;

/** Scene-wide material decisions made before packing: medium ids, tables, features. */
export interface MaterialPlan {
  readonly energyCompensation: boolean;
  /** 1-based medium id of every refractive-solid material (KHR_materials_volume). */
  readonly mediumIds: ReadonlyMap<NormalizedMaterial, number>;
  /** The materials with a medium, in id order. */
  readonly media: readonly NormalizedMaterial[];
  readonly tables: Record<keyof AlbedoTables | 'media' | 'spectral', boolean>;
  readonly uses: Readonly<MaterialFeatureUses>;
}

/**
 * Plans the materials of a scene: assigns medium ids (at most MAX_MEDIA refractive-solid
 * materials, a typed error naming the first material beyond that otherwise) and decides which
 * tables the heap needs. `fields` names each material for errors.
 */
export function planMaterials(materials: readonly NormalizedMaterial[], options: { energyCompensation?: boolean; fields?: readonly string[] } = {}): MaterialPlan {
  const energyCompensation = options.energyCompensation === true;
  const mediumIds = new Map<NormalizedMaterial, number>();
  const media: NormalizedMaterial[] = [];
  const any = (p: (m: NormalizedMaterial) => boolean): boolean => materials.some(p);
  materials.forEach((m, i) => {
    if (!m.volume || mediumIds.has(m)) return;
    if (media.length >= MAX_MEDIA) {
      throw new GpuRendererError('SCENE_TOO_LARGE', `at most ${MAX_MEDIA} refractive-solid (KHR_materials_volume) materials are supported`, { field: options.fields?.[i] ?? `materials[${i}]` });
    }
    media.push(m);
    mediumIds.set(m, media.length);
  });
  const uses = Object.fromEntries(anyMaterialExtensions.map((e) => [e.key, any((m) => extensionOf(m, e) !== undefined)])) as MaterialFeatureUses;
  uses.energyCompensation = energyCompensation && any(hasCompensableLobe);
  const tables: MaterialPlan['tables'] = {
    ggx: uses.energyCompensation,
    dielectric: uses.energyCompensation,
    dielectricTransmission: uses.energyCompensation && uses.transmission,
    clearcoat: false,
    sheen: false,
    media: false,
    spectral: false,
  };
  for (const e of anyMaterialExtensions) for (const t of e.tables ?? []) if (uses[e.key as MaterialExtensionKey]) tables[t] = true;
  return { energyCompensation, mediumIds, media, tables, uses };
}

/** One vec4 cell of a float table (four entries). */
const tableCellLayout: StructLayout = defineStructLayout('TableCell', 1, [['v', 'vec4f']]);

/** Appends a float table to the heap, four entries per vec4 (consecutive cells); returns its offset. */
function appendFloats(heap: Vec4Heap, values: Float32Array): number {
  const offset = heap.size;
  for (let c = 0; c < values.length; c += 4) heap.append(tableCellLayout, { v: values.subarray(c, c + 4) });
  return offset;
}

export { absorptionCoefficient };

/** A material's normalized block of extension `e` (undefined: absent). */
function extensionOf(m: NormalizedMaterial, e: MaterialExtensionSpec<never>): unknown {
  return (m as unknown as Record<string, unknown>)[e.key];
}

/** Whether extension `e` of material `m` reaches the GPU (its flag and block). */
function packedExtension(m: NormalizedMaterial, e: MaterialExtensionSpec<never>, context: PackContext): boolean {
  return extensionOf(m, e) !== undefined && (e.packed?.(context) ?? true);
}

/**
 * Writes the MaterialTables directory and the tables the plan needs at MATERIAL_TABLES_OFFSET:
 * it must be the heap's first record (the kernels find it at that constant offset). Nothing is
 * written when no material needs a table.
 */
export function packMaterialTables(heap: Vec4Heap, plan: MaterialPlan): void {
  const t = plan.tables;
  if (!Object.values(t).some(Boolean)) return;
  if (heap.size !== MATERIAL_TABLES_OFFSET) throw new Error('the material tables must open the materials heap');
  const header = heap.reserve(materialTablesLayout);
  const table = (name: keyof AlbedoTables): number => (t[name] ? appendFloats(heap, packedAlbedoTable(name)) : INDEX_NONE);
  const values: Record<string, number> = {
    ggxAlbedo: table('ggx'),
    dielectricAlbedo: table('dielectric'),
    dielectricTransmission: table('dielectricTransmission'),
    clearcoatAlbedo: table('clearcoat'),
    sheenAlbedo: table('sheen'),
    spectral: t.spectral ? appendFloats(heap, spectralResponseTable()) : INDEX_NONE,
    media: INDEX_NONE,
    mediumCount: plan.media.length,
  };
  if (t.media) {
    values.media = heap.size;
    for (const m of plan.media) {
      heap.append(mediumRecordLayout, { attenuation: absorptionCoefficient(m.volume!), ior: m.ior, dispersion: m.dispersion ?? 0 });
    }
  }
  heap.write(materialTablesLayout, header, values);
}

const alphaModeIds = { OPAQUE: ALPHA_MODE_OPAQUE, MASK: ALPHA_MODE_MASK, BLEND: ALPHA_MODE_BLEND } as const;

function packBinding(heap: Vec4Heap, ref: NormalizedTextureRef | undefined, srgb: boolean, infoOffset: TextureInfoOffsets): number {
  if (!ref) return INDEX_NONE;
  return heap.append(textureBindingLayout, {
    ...ref.transform,
    texture: infoOffset(ref.texture, srgb),
    texCoord: ref.texCoord,
    scale: ref.scale,
    flags: srgb ? TEXTURE_BINDING_FLAG_SRGB : 0,
  });
}

/**
 * Whether multiple-scattering compensation changes a material: it has a rough microfacet lobe (a
 * conductor, a Fresnel layer of ior other than 1, or an extension's lobe). Lambertian materials
 * (metallic 0, ior 1, no extension) and smooth ones have none, so they skip the table lookups.
 */
export function hasCompensableLobe(m: NormalizedMaterial): boolean {
  if (anyMaterialExtensions.some((e) => e.compensable && extensionOf(m, e) !== undefined)) return true;
  return m.roughness > 0 && (m.metallic > 0 || m.ior !== 1);
}

/** The MATERIAL_FLAG_* bits of a material's KHR extensions. */
export function materialExtensionFlags(m: NormalizedMaterial, plan: MaterialPlan): number {
  let flags = 0;
  const context: PackContext = { medium: plan.mediumIds.get(m) };
  for (const e of anyMaterialExtensions) if (packedExtension(m, e, context)) flags |= 1 << e.flag.bit;
  if (plan.energyCompensation && hasCompensableLobe(m)) flags |= MATERIAL_FLAG_ENERGY_COMPENSATION;
  if (m.ior === 0) flags |= MATERIAL_FLAG_IOR_INFINITE;
  return flags;
}

/**
 * Appends every material to the heap: a MaterialCore, its texture bindings and its KHR extension
 * blocks (the occlusion texture is not bound: the path tracer computes occlusion itself). Returns
 * each core's offset.
 */
export function packMaterials(heap: Vec4Heap, materials: readonly NormalizedMaterial[], infoOffset: TextureInfoOffsets, plan: MaterialPlan = planMaterials(materials)): number[] {
  const bind = (ref: NormalizedTextureRef | undefined, srgb: boolean): number => packBinding(heap, ref, srgb, infoOffset);
  return materials.map((m) => {
    const core = heap.reserve(materialCoreLayout);
    const context: PackContext = { medium: plan.mediumIds.get(m) };
    // Each extension block is reserved before its texture bindings are appended.
    const blocks: Record<string, number> = {};
    for (const e of anyMaterialExtensions) {
      if (!e.block) continue;
      blocks[e.key] = INDEX_NONE;
      if (!packedExtension(m, e, context)) continue;
      const offset = heap.reserve(e.block.layout);
      heap.write(e.block.layout, offset, e.block.pack(extensionOf(m, e) as never, bind, context));
      blocks[e.key] = offset;
    }
    heap.write(materialCoreLayout, core, {
      baseColor: m.baseColor,
      emission: m.emission,
      metallic: m.metallic,
      roughness: m.roughness,
      ior: m.ior,
      alphaCutoff: m.alphaCutoff,
      flags: (m.doubleSided ? MATERIAL_FLAG_DOUBLE_SIDED : 0) | (alphaModeIds[m.alphaMode] << MATERIAL_ALPHA_MODE_SHIFT) | materialExtensionFlags(m, plan),
      baseColorTexture: bind(m.baseColorTexture, true),
      metallicRoughnessTexture: bind(m.metallicRoughnessTexture, false),
      normalTexture: bind(m.normalTexture, false),
      emissiveTexture: bind(m.emissiveTexture, true),
      ...blocks,
      dispersion: m.dispersion ?? 0,
    });
    return core;
  });
}

/** Upper bound of the heap cells the materials take (cores, blocks, bindings), before tables. */
export function materialHeapCells(materials: readonly NormalizedMaterial[]): number {
  const binding = textureBindingLayout.size / 16;
  let cells = 0;
  for (const m of materials) {
    cells += materialCoreLayout.size / 16 + materialTextureRefs(m).length * binding;
    for (const e of anyMaterialExtensions) if (e.block && extensionOf(m, e) !== undefined) cells += e.block.layout.size / 16;
  }
  return cells;
}
