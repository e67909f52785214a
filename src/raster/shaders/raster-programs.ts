/**
 * The raster renderer's GPU programs: a root WESL module each and the binding set its bindings come
 * from. `npm run generate` links them with the package's WESL project (the same linker and sources
 * as the path tracer's programs, so tone mapping, colour and microfacet code is shared) into
 * raster-programs.generated.ts.
 */
import type { RasterBindingSet } from '../gpu/raster-bindings.ts';

export interface RasterProgramSpec {
  readonly module: string;
  readonly set: RasterBindingSet;
}

export const rasterProgramSpecs = {
  forward: { module: 'package::raster::shaders::forward', set: 'draw' },
  shadow: { module: 'package::raster::shaders::shadow', set: 'draw' },
  background: { module: 'package::raster::shaders::background', set: 'draw' },
  skin: { module: 'package::raster::shaders::skin', set: 'skin' },
  iblDownsample: { module: 'package::raster::shaders::ibl_downsample', set: 'ibl' },
  iblPrefilter: { module: 'package::raster::shaders::ibl_prefilter', set: 'ibl' },
  iblIrradiance: { module: 'package::raster::shaders::ibl_irradiance', set: 'ibl' },
  brdfLut: { module: 'package::raster::shaders::brdf_lut', set: 'ibl' },
  resolve: { module: 'package::raster::shaders::resolve', set: 'resolve' },
} as const satisfies Record<string, RasterProgramSpec>;

export type RasterProgramName = keyof typeof rasterProgramSpecs;
