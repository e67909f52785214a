/** KHR_materials_clearcoat: a dielectric GGX coat (ior 1.5) over the material (physics: layer.wesl, reference.ts). */
import { defineStructLayout } from '../../../gpu-layout/struct-layout.ts';
import { defineMaterialExtension } from '../material-extension.ts';

export const clearcoatBlockLayout = defineStructLayout('ClearcoatBlock', 1, [
  ['clearcoat', 'f32', 'clearcoatFactor'],
  ['roughness', 'f32', 'clearcoatRoughnessFactor'],
  ['clearcoatTexture', 'u32', 'R channel'],
  ['roughnessTexture', 'u32', 'G channel'],
  ['normalTexture', 'u32', 'tangent-space normal map of the coat (scale in the binding)'],
  ['reserved0', 'u32'],
  ['reserved1', 'u32'],
  ['reserved2', 'u32'],
]);

export const clearcoat = defineMaterialExtension({
  name: 'KHR_materials_clearcoat',
  key: 'clearcoat',
  factors: [
    { key: 'clearcoatFactor', field: 'factor', type: 'number', default: 0, range: { min: 0, max: 1 }, doc: 'coat strength, default 0' },
    { key: 'clearcoatRoughnessFactor', field: 'roughnessFactor', type: 'number', default: 0, range: { min: 0, max: 1 }, doc: 'coat roughness, default 0' },
  ],
  textures: [
    { key: 'clearcoatTexture', field: 'texture', srgb: false },
    { key: 'clearcoatRoughnessTexture', field: 'roughnessTexture', srgb: false },
    { key: 'clearcoatNormalTexture', field: 'normalTexture', srgb: false, scaleGetter: 'getClearcoatNormalScale' },
  ],
  enabledBy: 'clearcoatFactor',
  feature: { name: 'FEATURE_CLEARCOAT', doc: 'KHR_materials_clearcoat' },
  flag: { name: 'MATERIAL_FLAG_CLEARCOAT', bit: 11 },
  compensable: true,
  tables: ['clearcoat'],
  raster: 'drawn',
  layer: { folder: 'clearcoat' },
}, {
  present: (b) => b.factor > 0,
  block: {
    layout: clearcoatBlockLayout,
    pack: (b, bind) => ({
      clearcoat: b.factor, roughness: b.roughnessFactor, clearcoatTexture: bind(b.texture, false), roughnessTexture: bind(b.roughnessTexture, false),
      normalTexture: bind(b.normalTexture, false),
    }),
  },
});
