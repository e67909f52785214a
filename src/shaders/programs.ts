/**
 * Every GPU program the package ships: a root WESL module (path under src/, `::`-separated, as in
 * `import` statements) and its entry points. `npm run generate` links each program with the WESL
 * linker, reflects the bindings and `override` constants that survive linking, and writes
 * programs.generated.ts, which the runtime reads.
 */
export interface ProgramSpec {
  /** Root module, e.g. `package::pathtracer::kernels::trace`. */
  readonly module: string;
  /** Which binding table the program's bindings come from. */
  readonly bindings: 'pathTracer' | 'display' | 'bvhBuild' | 'oidn';
  /** WESL `@if` conditions the program is linked with (e.g. `f16`). */
  readonly conditions?: Readonly<Record<string, boolean>>;
}

export const programSpecs = {
  camera: { module: 'package::pathtracer::kernels::camera', bindings: 'pathTracer' },
  trace: { module: 'package::pathtracer::kernels::trace', bindings: 'pathTracer' },
  shade: { module: 'package::pathtracer::kernels::shade', bindings: 'pathTracer' },
  accumulate: { module: 'package::film::accumulation::accumulate', bindings: 'pathTracer' },
  adaptiveSampling: { module: 'package::film::adaptive::adaptive_sampling', bindings: 'pathTracer' },
  denoiseInput: { module: 'package::film::denoise::atrous_input', bindings: 'pathTracer' },
  denoise: { module: 'package::film::denoise::atrous', bindings: 'pathTracer' },
  resolve: { module: 'package::film::display::resolve', bindings: 'display' },
  present: { module: 'package::film::display::present', bindings: 'display' },
  // The GPU BVH builder and refitter (src/accel/gpu-build/), one program per group of passes so
  // each pipeline layout stays within the default 8 storage buffers per stage.
  bvhMorton: { module: 'package::accel::gpu_build::morton', bindings: 'bvhBuild' },
  bvhSort: { module: 'package::accel::gpu_build::radix_sort', bindings: 'bvhBuild' },
  bvhScan: { module: 'package::accel::gpu_build::prefix_scan', bindings: 'bvhBuild' },
  bvhHierarchy: { module: 'package::accel::gpu_build::lbvh_hierarchy', bindings: 'bvhBuild' },
  bvhGather: { module: 'package::accel::gpu_build::gather', bindings: 'bvhBuild' },
  bvhFit: { module: 'package::accel::gpu_build::lbvh_fit', bindings: 'bvhBuild' },
  bvhEmit: { module: 'package::accel::gpu_build::lbvh_emit', bindings: 'bvhBuild' },
  bvhSummary: { module: 'package::accel::gpu_build::lbvh_summary', bindings: 'bvhBuild' },
  bvhRefit: { module: 'package::accel::gpu_build::refit', bindings: 'bvhBuild' },
  oidnConv: { module: 'package::film::denoise::oidn::conv', bindings: 'oidn' },
  oidnConvF16: { module: 'package::film::denoise::oidn::conv', bindings: 'oidn', conditions: { f16: true } },
  oidnExposure: { module: 'package::film::denoise::oidn::exposure', bindings: 'oidn' },
  oidnInput: { module: 'package::film::denoise::oidn::input', bindings: 'oidn' },
  oidnInputF16: { module: 'package::film::denoise::oidn::input', bindings: 'oidn', conditions: { f16: true } },
  oidnOutput: { module: 'package::film::denoise::oidn::output', bindings: 'oidn' },
  oidnOutputF16: { module: 'package::film::denoise::oidn::output', bindings: 'oidn', conditions: { f16: true } },
} as const satisfies Record<string, ProgramSpec>;

export type ProgramName = keyof typeof programSpecs;
