/** KHR_materials_diffuse_transmission: the fraction of the diffuse lobe scattered to the back side. */
import { defineStructLayout } from '../../../gpu-layout/struct-layout.ts';
import { defineMaterialExtension } from '../material-extension.ts';

export const diffuseTransmissionBlockLayout = defineStructLayout('DiffuseTransmissionBlock', 1, [
  ['color', 'vec3f', 'diffuseTransmissionColorFactor'],
  ['diffuseTransmission', 'f32', 'diffuseTransmissionFactor'],
  ['texture', 'u32', 'A channel'],
  ['colorTexture', 'u32', 'RGB, sRGB'],
  ['reserved0', 'u32'],
  ['reserved1', 'u32'],
]);

export const diffuseTransmission = defineMaterialExtension({
  name: 'KHR_materials_diffuse_transmission',
  key: 'diffuseTransmission',
  factors: [
    { key: 'diffuseTransmissionFactor', field: 'factor', type: 'number', default: 0, range: { min: 0, max: 1 }, doc: 'diffusely transmitted fraction, default 0' },
    { key: 'diffuseTransmissionColorFactor', field: 'colorFactor', type: 'rgb', default: [1, 1, 1], range: { min: 0, max: 1 }, doc: 'transmitted colour, linear RGB, default [1, 1, 1]' },
  ],
  textures: [
    { key: 'diffuseTransmissionTexture', field: 'texture', srgb: false },
    { key: 'diffuseTransmissionColorTexture', field: 'colorTexture', srgb: true },
  ],
  enabledBy: 'diffuseTransmissionFactor',
  feature: { name: 'FEATURE_DIFFUSE_TRANSMISSION', doc: 'KHR_materials_diffuse_transmission' },
  flag: { name: 'MATERIAL_FLAG_DIFFUSE_TRANSMISSION', bit: 15 },
  compensable: true,
  raster: 'refused',
}, {
  present: (b) => b.factor > 0,
  block: {
    layout: diffuseTransmissionBlockLayout,
    pack: (b, bind) => ({ color: b.colorFactor, diffuseTransmission: b.factor, texture: bind(b.texture, false), colorTexture: bind(b.colorTexture, true) }),
  },
});
