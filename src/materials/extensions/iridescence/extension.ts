/** KHR_materials_iridescence: a thin film (Belcour and Barla 2017) over the specular lobes. */
import { defineStructLayout } from '../../../gpu-layout/struct-layout.ts';
import { defineMaterialExtension } from '../material-extension.ts';

export const iridescenceBlockLayout = defineStructLayout('IridescenceBlock', 1, [
  ['iridescence', 'f32', 'iridescenceFactor'],
  ['ior', 'f32', 'iridescenceIor of the thin film'],
  ['thicknessMinimum', 'f32', 'nanometres at thickness texture G = 0'],
  ['thicknessMaximum', 'f32', 'nanometres at G = 1 (and without a texture)'],
  ['iridescenceTexture', 'u32', 'R channel'],
  ['thicknessTexture', 'u32', 'G channel'],
  ['reserved0', 'u32'],
  ['reserved1', 'u32'],
]);

export const iridescence = defineMaterialExtension({
  name: 'KHR_materials_iridescence',
  key: 'iridescence',
  factors: [
    { key: 'iridescenceFactor', field: 'factor', type: 'number', default: 0, range: { min: 0, max: 1 }, doc: 'film strength, default 0' },
    { key: 'iridescenceIor', field: 'ior', type: 'number', default: 1.3, range: { min: 1 }, getter: 'getIridescenceIOR', doc: 'film ior, default 1.3' },
    { key: 'iridescenceThicknessMinimum', field: 'thicknessMinimum', type: 'number', default: 100, range: { min: 0 }, doc: 'film thickness in nm at texture G = 0, default 100' },
    { key: 'iridescenceThicknessMaximum', field: 'thicknessMaximum', type: 'number', default: 400, range: { min: 0 }, doc: 'film thickness in nm at G = 1, default 400' },
  ],
  textures: [
    { key: 'iridescenceTexture', field: 'texture', srgb: false },
    { key: 'iridescenceThicknessTexture', field: 'thicknessTexture', srgb: false },
  ],
  enabledBy: 'iridescenceFactor',
  feature: { name: 'FEATURE_IRIDESCENCE', doc: 'KHR_materials_iridescence (thin-film Fresnel)' },
  flag: { name: 'MATERIAL_FLAG_IRIDESCENCE', bit: 13 },
  compensable: true,
  raster: 'refused',
}, {
  present: (b) => b.factor > 0,
  block: {
    layout: iridescenceBlockLayout,
    pack: (b, bind) => ({
      iridescence: b.factor, ior: b.ior, thicknessMinimum: b.thicknessMinimum, thicknessMaximum: b.thicknessMaximum,
      iridescenceTexture: bind(b.texture, false), thicknessTexture: bind(b.thicknessTexture, false),
    }),
  },
});
