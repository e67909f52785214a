import { allocateStructArray, writeStruct } from '../gpu-layout/struct-layout.ts';
import { MATERIAL_FLAG_DOUBLE_SIDED, materialLayout } from '../gpu-layout/records.ts';
import type { NormalizedMaterial } from './material.ts';

/** Material records in slot order (one default record when there are none). */
export function packWavefrontMaterials(materials: readonly NormalizedMaterial[]): ArrayBuffer {
  const buffer = allocateStructArray(materialLayout, materials.length);
  const view = new DataView(buffer);
  materials.forEach((m, i) => {
    writeStruct(materialLayout, view, i, {
      baseColor: m.baseColor,
      emission: m.emission,
      metallic: m.metallic,
      roughness: m.roughness,
      ior: m.ior,
      transmission: 0,
      flags: m.doubleSided ? MATERIAL_FLAG_DOUBLE_SIDED : 0,
      specularColor: [1, 1, 1],
      specular: 1,
    });
  });
  return buffer;
}
