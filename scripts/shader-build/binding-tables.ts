/**
 * The binding table of each program group (src/shaders/programs.ts): the build checks every
 * binding a linked program keeps against it. At run time each group's code hands its own table to
 * the program layer (src/shaders/program-pipelines.ts), which sits below all of them.
 */
import { bvhBuildBindings } from '../../src/accel/gpu-build/bindings.ts';
import { pathTracerBindings, type BindingSpec } from '../../src/gpu-layout/bindings.ts';
import { oidnBindings } from '../../src/film/denoise/oidn/bindings.ts';
import { rasterBindings } from '../../src/raster/gpu/raster-bindings.ts';
import { displayBindings } from '../../src/shaders/display-bindings.ts';
import type { ProgramGroupName } from '../../src/shaders/programs.ts';

export const bindingTables: Readonly<Record<ProgramGroupName, Readonly<Record<string, BindingSpec & { set?: string }>>>> = {
  pathTracer: pathTracerBindings,
  display: displayBindings,
  bvhBuild: bvhBuildBindings,
  oidn: oidnBindings,
  raster: rasterBindings,
};
