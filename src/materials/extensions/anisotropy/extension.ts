/** KHR_materials_anisotropy: anisotropic GGX along a rotated tangent direction. */
import { defineStructLayout } from '../../../gpu-layout/struct-layout.ts';
import { defineMaterialExtension } from '../material-extension.ts';

export const anisotropyBlockLayout = defineStructLayout('AnisotropyBlock', 1, [
  ['strength', 'f32', 'anisotropyStrength'],
  ['rotationCos', 'f32', 'cos(anisotropyRotation)'],
  ['rotationSin', 'f32', 'sin(anisotropyRotation)'],
  ['texture', 'u32', 'RG direction in [-1, 1] tangent space, B strength'],
]);

export const anisotropy = defineMaterialExtension({
  name: 'KHR_materials_anisotropy',
  key: 'anisotropy',
  factors: [
    { key: 'anisotropyStrength', field: 'strength', type: 'number', default: 0, range: { min: 0, max: 1 }, doc: 'anisotropy strength, default 0' },
    { key: 'anisotropyRotation', field: 'rotation', type: 'number', default: 0, range: {}, doc: 'radians counter-clockwise from the tangent, default 0' },
  ],
  textures: [{ key: 'anisotropyTexture', field: 'texture', srgb: false }],
  enabledBy: 'anisotropyStrength',
  feature: { name: 'FEATURE_ANISOTROPY', doc: 'KHR_materials_anisotropy (anisotropic GGX)' },
  flag: { name: 'MATERIAL_FLAG_ANISOTROPY', bit: 14 },
  compensable: true,
  raster: 'refused',
}, {
  present: (b) => b.strength > 0,
  block: {
    layout: anisotropyBlockLayout,
    pack: (b, bind) => ({ strength: b.strength, rotationCos: Math.cos(b.rotation), rotationSin: Math.sin(b.rotation), texture: bind(b.texture, false) }),
  },
});
