/**
 * The binding table of each program group (src/shaders/programs.ts): the build checks every
 * binding a linked program keeps against it, and pipeline layouts are built from it.
 */
import { bvhBuildBindings } from '../accel/gpu-build/bindings.ts';
import { pathTracerBindings, type BindingSpec } from '../gpu-layout/bindings.ts';
import { oidnBindings } from '../post/denoise/oidn/bindings.ts';
import { rasterBindings } from '../raster/gpu/raster-bindings.ts';
import { displayBindings } from './display-bindings.ts';
import type { ProgramGroupName } from './programs.ts';

export const bindingTables: Readonly<Record<ProgramGroupName, Readonly<Record<string, BindingSpec & { set?: string }>>>> = {
  pathTracer: pathTracerBindings,
  display: displayBindings,
  bvhBuild: bvhBuildBindings,
  oidn: oidnBindings,
  raster: rasterBindings,
};
