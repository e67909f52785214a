/** KHR_materials_specular: the strength and F0 colour of the dielectric specular lobe. */
import { defineStructLayout } from '../../../gpu-layout/struct-layout.ts';
import { defineMaterialExtension } from '../material-extension.ts';

export const specularBlockLayout = defineStructLayout('SpecularBlock', 1, [
  ['specularColor', 'vec3f', 'specularColorFactor (may exceed 1)'],
  ['specular', 'f32', 'specularFactor'],
  ['specularTexture', 'u32', 'A channel'],
  ['specularColorTexture', 'u32', 'RGB, sRGB'],
  ['reserved0', 'u32'],
  ['reserved1', 'u32'],
]);

export const specular = defineMaterialExtension({
  name: 'KHR_materials_specular',
  key: 'specular',
  factors: [
    { key: 'specularFactor', field: 'factor', type: 'number', default: 1, range: { min: 0, max: 1 }, doc: 'specular strength, default 1' },
    { key: 'specularColorFactor', field: 'colorFactor', type: 'rgb', default: [1, 1, 1], range: { min: 0 }, doc: 'F0 colour, linear RGB, default [1, 1, 1]; may exceed 1 (the product with the IOR\'s F0 is clamped to 1)' },
  ],
  textures: [
    { key: 'specularTexture', field: 'texture', srgb: false },
    { key: 'specularColorTexture', field: 'colorTexture', srgb: true },
  ],
  enabledBy: 'specularFactor',
  feature: { name: 'FEATURE_SPECULAR', doc: 'KHR_materials_specular: specular weight and F0 colour' },
  flag: { name: 'MATERIAL_FLAG_SPECULAR', bit: 8 },
  compensable: true,
  raster: 'drawn',
}, {
  // Present whenever it changes the material: any factor off its default, or a texture.
  present: (b) => b.factor !== 1 || b.colorFactor.some((c) => c !== 1) || b.texture !== undefined || b.colorTexture !== undefined,
  block: {
    layout: specularBlockLayout,
    pack: (b, bind) => ({ specularColor: b.colorFactor, specular: b.factor, specularTexture: bind(b.texture, false), specularColorTexture: bind(b.colorTexture, true) }),
  },
});
