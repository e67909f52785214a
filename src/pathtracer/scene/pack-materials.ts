import { INDEX_NONE, MATERIAL_ALPHA_MODE_SHIFT, MATERIAL_FLAG_DOUBLE_SIDED, ALPHA_MODE_BLEND, ALPHA_MODE_MASK, ALPHA_MODE_OPAQUE, TEXTURE_BINDING_FLAG_SRGB } from '../../gpu-layout/constants.ts';
import { materialCoreLayout, textureBindingLayout } from '../../gpu-layout/records.ts';
import type { Vec4Heap } from '../../gpu-layout/vec4-heap.ts';
import { coreTextureSlots, type CoreTextureSlot, type NormalizedMaterial, type NormalizedTextureRef } from '../../scene/material.ts';

/** Heap offset of the TextureInfo of texture `texture` decoded as sRGB or linear data. */
export type TextureInfoOffsets = (texture: number, srgb: boolean) => number;

/** Every (texture, colour space) pair the materials sample: what the atlas must hold. */
export function textureUsages(materials: readonly NormalizedMaterial[]): { texture: number; srgb: boolean }[] {
  const seen = new Map<string, { texture: number; srgb: boolean }>();
  for (const m of materials) {
    for (const slot of Object.keys(coreTextureSlots) as CoreTextureSlot[]) {
      const ref = m[slot];
      if (ref && slot !== 'occlusionTexture') {
        const srgb = coreTextureSlots[slot].srgb;
        seen.set(`${ref.texture}:${srgb}`, { texture: ref.texture, srgb });
      }
    }
  }
  return [...seen.values()];
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
 * Appends every material to the heap: a MaterialCore plus its texture bindings (the occlusion
 * texture is not bound: the path tracer computes occlusion itself). Returns each core's offset.
 */
export function packMaterials(heap: Vec4Heap, materials: readonly NormalizedMaterial[], infoOffset: TextureInfoOffsets): number[] {
  return materials.map((m) => {
    const core = heap.reserve(materialCoreLayout);
    heap.write(materialCoreLayout, core, {
      baseColor: m.baseColor,
      emission: m.emission,
      metallic: m.metallic,
      roughness: m.roughness,
      ior: m.ior,
      alphaCutoff: m.alphaCutoff,
      flags: (m.doubleSided ? MATERIAL_FLAG_DOUBLE_SIDED : 0) | (alphaModeIds[m.alphaMode] << MATERIAL_ALPHA_MODE_SHIFT),
      baseColorTexture: packBinding(heap, m.baseColorTexture, true, infoOffset),
      metallicRoughnessTexture: packBinding(heap, m.metallicRoughnessTexture, false, infoOffset),
      normalTexture: packBinding(heap, m.normalTexture, false, infoOffset),
      emissiveTexture: packBinding(heap, m.emissiveTexture, true, infoOffset),
      specular: INDEX_NONE,
      transmission: INDEX_NONE,
      volume: INDEX_NONE,
      clearcoat: INDEX_NONE,
      sheen: INDEX_NONE,
      iridescence: INDEX_NONE,
      anisotropy: INDEX_NONE,
      diffuseTransmission: INDEX_NONE,
      dispersion: 0,
    });
    return core;
  });
}
