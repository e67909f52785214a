import { structLayoutToWgsl } from '../gpu-layout/struct-layout.ts';
import * as records from '../gpu-layout/records.ts';

/** WGSL declarations of every GPU record plus the shared constants, generated from records.ts. */
export function createRecordsWgsl(): string {
  const structs = Object.values(records.wavefrontRecordLayouts).map(structLayoutToWgsl).join('\n');
  const u32Constants: Record<string, number> = {
    PRIMITIVE_KIND_TRIANGLE: records.PRIMITIVE_KIND_TRIANGLE,
    PRIMITIVE_KIND_SPHERE: records.PRIMITIVE_KIND_SPHERE,
    PRIMITIVE_KIND_BOX: records.PRIMITIVE_KIND_BOX,
    PRIMITIVE_NONE: records.PRIMITIVE_NONE,
    SCENE_OBJECT_SPHERE: records.SCENE_OBJECT_SPHERE,
    SCENE_OBJECT_BOX: records.SCENE_OBJECT_BOX,
    MATERIAL_FLAG_DOUBLE_SIDED: records.MATERIAL_FLAG_DOUBLE_SIDED,
    TRIANGLE_FLAG_HAS_NORMALS: records.TRIANGLE_FLAG_HAS_NORMALS,
    TRIANGLE_FLAG_HAS_UVS: records.TRIANGLE_FLAG_HAS_UVS,
    PATH_FLAG_SPECULAR_BOUNCE: records.PATH_FLAG_SPECULAR_BOUNCE,
    LIGHT_FLAG_DOUBLE_SIDED: records.LIGHT_FLAG_DOUBLE_SIDED,
    QUEUE_COUNTER_COUNT: records.queueCounterCount,
    WORKGROUP_SIZE: records.rendererWavefrontComputeWorkgroupSize,
    RUSSIAN_ROULETTE_DEPTH: records.russianRouletteStartDepth,
  };
  for (const [name, slot] of Object.entries(records.queueCounterSlots)) {
    u32Constants[`COUNTER_${name.replace(/([A-Z])/g, '_$1').toUpperCase()}`] = slot;
  }
  const constants = Object.entries(u32Constants)
    .map(([name, value]) => `const ${name}: u32 = ${value >>> 0}u;`)
    .join('\n');
  return `${structs}\n${constants}\n`;
}
