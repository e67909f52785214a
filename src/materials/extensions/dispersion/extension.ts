/**
 * KHR_materials_dispersion: 20 / Abbe number of a refractive solid. It bends light only inside a
 * volume, so it is kept only with one; stored in MaterialCore and the medium, no block of its own.
 */
import { defineMaterialExtension } from '../material-extension.ts';

export const dispersion = defineMaterialExtension({
  name: 'KHR_materials_dispersion',
  key: 'dispersion',
  normalized: 'scalar',
  factors: [{ key: 'dispersion', field: 'dispersion', type: 'number', default: 0, range: { min: 0 }, doc: '20 / Abbe number, default 0' }],
  textures: [],
  enabledBy: 'dispersion',
  feature: { name: 'FEATURE_DISPERSION', doc: 'KHR_materials_dispersion: paths that meet it carry one wavelength' },
  flag: { name: 'MATERIAL_FLAG_DISPERSION', bit: 16 },
  compensable: false,
  tables: ['spectral'],
  raster: 'refused',
}, {
  packed: (c) => c.medium !== undefined,
  present: (d, m) => d > 0 && m.volume !== undefined,
});
