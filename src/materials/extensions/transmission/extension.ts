/** KHR_materials_transmission: the fraction of light the specular lobe transmits. */
import { defineStructLayout } from '../../../gpu-layout/struct-layout.ts';
import { defineMaterialExtension } from '../material-extension.ts';

export const transmissionBlockLayout = defineStructLayout('TransmissionBlock', 1, [
  ['transmission', 'f32', 'transmissionFactor'],
  ['transmissionTexture', 'u32', 'R channel'],
  ['reserved0', 'u32'],
  ['reserved1', 'u32'],
]);

export const transmission = defineMaterialExtension({
  name: 'KHR_materials_transmission',
  key: 'transmission',
  factors: [{ key: 'transmissionFactor', field: 'factor', type: 'number', default: 0, range: { min: 0, max: 1 }, doc: 'transmitted fraction, default 0' }],
  textures: [{ key: 'transmissionTexture', field: 'texture', srgb: false }],
  enabledBy: 'transmissionFactor',
  feature: { name: 'FEATURE_TRANSMISSION', doc: 'KHR_materials_transmission: thin-walled and refractive GGX transmission' },
  flag: { name: 'MATERIAL_FLAG_TRANSMISSION', bit: 9 },
  compensable: true,
  raster: 'drawn',
}, {
  present: (b) => b.factor > 0,
  block: {
    layout: transmissionBlockLayout,
    pack: (b, bind) => ({ transmission: b.factor, transmissionTexture: bind(b.texture, false) }),
  },
});
