/**
 * KHR_materials_volume: a refractive solid (thicknessFactor > 0 on a transmitting material) with
 * Beer-Lambert absorption. Only a solid that light can enter is a volume; it gets a medium id
 * (the material plan) and its MediumRecord in the material tables.
 */
import { defineStructLayout } from '../../../gpu-layout/struct-layout.ts';
import { defineMaterialExtension } from '../material-extension.ts';
import { absorptionCoefficient } from './absorption.ts';

/** Present only for a refractive solid (thicknessFactor > 0). */
export const volumeBlockLayout = defineStructLayout('VolumeBlock', 1, [
  ['attenuation', 'vec3f', 'absorption coefficient -ln(attenuationColor) / attenuationDistance per unit length'],
  ['thickness', 'f32', 'thicknessFactor (the path tracer takes thickness from the geometry)'],
  ['thicknessTexture', 'u32', 'G channel (loaded for raster renderers)'],
  ['medium', 'u32', 'medium id (1-based index into the media table)'],
  ['reserved0', 'u32'],
  ['reserved1', 'u32'],
]);

export const volume = defineMaterialExtension({
  name: 'KHR_materials_volume',
  key: 'volume',
  factors: [
    { key: 'thicknessFactor', field: 'thicknessFactor', type: 'number', default: 0, range: { min: 0 }, doc: '> 0 makes the mesh a refractive solid; default 0 (thin walled)' },
    { key: 'attenuationColor', field: 'attenuationColor', type: 'rgb', default: [1, 1, 1], range: { min: 0, max: 1 }, doc: 'colour white light reaches after attenuationDistance, linear RGB, default [1, 1, 1]' },
    { key: 'attenuationDistance', field: 'attenuationDistance', type: 'number', default: Infinity, range: { above: 0 }, infinity: true, doc: 'default Infinity (no absorption)' },
  ],
  textures: [{ key: 'thicknessTexture', field: 'thicknessTexture', srgb: false }],
  enabledBy: 'thicknessFactor',
  feature: { name: 'FEATURE_VOLUME', doc: 'KHR_materials_volume: refractive solids, nested media, Beer-Lambert absorption' },
  flag: { name: 'MATERIAL_FLAG_VOLUME', bit: 10 },
  compensable: false,
  tables: ['media'],
  raster: 'drawn',
}, {
  packed: (c) => c.medium !== undefined,
  present: (b, m) => b.thicknessFactor > 0 && (m.transmission !== undefined || m.diffuseTransmission !== undefined),
  block: {
    layout: volumeBlockLayout,
    pack: (b, bind, c) => ({ attenuation: absorptionCoefficient(b), thickness: b.thicknessFactor, thicknessTexture: bind(b.thicknessTexture, false), medium: c.medium! }),
  },
});
