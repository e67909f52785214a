/** KHR_materials_sheen: a Charlie sheen layer over the base (physics: layer.wesl, sheen-charlie.wesl, reference.ts). */
import { defineStructLayout } from '../../../gpu-layout/struct-layout.ts';
import { defineMaterialExtension } from '../material-extension.ts';

export const sheenBlockLayout = defineStructLayout('SheenBlock', 1, [
  ['color', 'vec3f', 'sheenColorFactor'],
  ['roughness', 'f32', 'sheenRoughnessFactor'],
  ['colorTexture', 'u32', 'RGB, sRGB'],
  ['roughnessTexture', 'u32', 'A channel'],
  ['reserved0', 'u32'],
  ['reserved1', 'u32'],
]);

export const sheen = defineMaterialExtension({
  name: 'KHR_materials_sheen',
  key: 'sheen',
  factors: [
    { key: 'sheenColorFactor', field: 'colorFactor', type: 'rgb', default: [0, 0, 0], range: { min: 0, max: 1 }, doc: 'sheen colour, linear RGB, default [0, 0, 0]' },
    { key: 'sheenRoughnessFactor', field: 'roughnessFactor', type: 'number', default: 0, range: { min: 0, max: 1 }, doc: 'sheen roughness, default 0' },
  ],
  textures: [
    { key: 'sheenColorTexture', field: 'colorTexture', srgb: true },
    { key: 'sheenRoughnessTexture', field: 'roughnessTexture', srgb: false },
  ],
  enabledBy: 'sheenColorFactor',
  feature: { name: 'FEATURE_SHEEN', doc: 'KHR_materials_sheen (Charlie)' },
  flag: { name: 'MATERIAL_FLAG_SHEEN', bit: 12 },
  compensable: true,
  tables: ['sheen'],
  raster: 'drawn',
  layer: { folder: 'sheen' },
}, {
  present: (b) => b.colorFactor.some((c) => c > 0),
  block: {
    layout: sheenBlockLayout,
    pack: (b, bind) => ({ color: b.colorFactor, roughness: b.roughnessFactor, colorTexture: bind(b.colorTexture, true), roughnessTexture: bind(b.roughnessTexture, false) }),
  },
});
