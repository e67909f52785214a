/**
 * Every GPU program the package ships, the path tracer's and the raster renderer's: a root WESL
 * module (path under src/, `::`-separated, as in `import` statements) and the group it belongs
 * to. `npm run generate` (scripts/shader-build/programs.ts) links each program with the WESL
 * linker, reflects the bindings and `override` constants that survive linking into
 * programs.generated.ts, and writes each group's WGSL to a module of its own
 * (wgsl/<file>.generated.ts). docs/gpu-programs.md describes the whole layer.
 */

/**
 * Program groups: a group's programs take their bindings from one binding table and ship in one
 * generated module, imported on first use, so a bundler splits each into a chunk of its own: an app
 * that only rasterizes never downloads the path tracer's WGSL, and one that never builds a BVH on
 * the GPU or runs the OIDN denoiser never downloads theirs. `shaderSource` marks the groups that
 * createWavefrontPathTracingComputeShaderSource() returns (bundled with that function).
 */
export const programGroups = {
  /** The wavefront kernels, adaptive sampling and the à-trous denoiser. */
  pathTracer: { file: 'path-tracer', shaderSource: true },
  /** Resolving the film for display and presenting it on a canvas. */
  display: { file: 'display', shaderSource: true },
  /** The GPU LBVH builder and refitter (acceleration mode 'gpu', and refits of the CPU tree). */
  bvhBuild: { file: 'bvh-build', shaderSource: false },
  /** The OIDN denoiser's network. */
  oidn: { file: 'oidn', shaderSource: false },
  /** The raster renderer (its renderer loads them when it is created). */
  raster: { file: 'raster', shaderSource: false },
} as const satisfies Record<string, { readonly file: string; readonly shaderSource: boolean }>;

export type ProgramGroupName = keyof typeof programGroups;

export interface ProgramSpec {
  /** Root module, e.g. `package::pathtracer::kernels::trace`. */
  readonly module: string;
  /** The program's group, which names the binding table its bindings come from. */
  readonly group: ProgramGroupName;
  /** WESL `@if` conditions the program is linked with (e.g. `f16`). */
  readonly conditions?: Readonly<Record<string, boolean>>;
  /** Where a group's table is split into sets (the raster's), the set the bindings come from. */
  readonly set?: string;
}

export const programSpecs = {
  camera: { module: 'package::pathtracer::kernels::camera', group: 'pathTracer' },
  trace: { module: 'package::pathtracer::kernels::trace', group: 'pathTracer' },
  shadingSize: { module: 'package::pathtracer::kernels::shading_size', group: 'pathTracer' },
  shade: { module: 'package::pathtracer::kernels::shade', group: 'pathTracer' },
  accumulate: { module: 'package::film::accumulation::accumulate', group: 'pathTracer' },
  // The megakernel integrator (integrator: 'megakernel'): the stage functions above in one loop.
  megakernel: { module: 'package::pathtracer::kernels::megakernel', group: 'pathTracer', conditions: { megakernel: true } },
  adaptiveSampling: { module: 'package::film::adaptive::adaptive_sampling', group: 'pathTracer' },
  denoiseInput: { module: 'package::film::denoise::atrous_input', group: 'pathTracer' },
  denoise: { module: 'package::film::denoise::atrous', group: 'pathTracer' },
  resolve: { module: 'package::film::display::resolve', group: 'display' },
  present: { module: 'package::film::display::present', group: 'display' },
  // The GPU BVH builder and refitter (src/accel/gpu-build/), one program per group of passes so
  // each pipeline layout stays within the default 8 storage buffers per stage.
  bvhMorton: { module: 'package::accel::gpu_build::morton', group: 'bvhBuild' },
  bvhSort: { module: 'package::accel::gpu_build::radix_sort', group: 'bvhBuild' },
  bvhScan: { module: 'package::accel::gpu_build::prefix_scan', group: 'bvhBuild' },
  bvhHierarchy: { module: 'package::accel::gpu_build::lbvh_hierarchy', group: 'bvhBuild' },
  bvhGather: { module: 'package::accel::gpu_build::gather', group: 'bvhBuild' },
  bvhFit: { module: 'package::accel::gpu_build::lbvh_fit', group: 'bvhBuild' },
  bvhEmit: { module: 'package::accel::gpu_build::lbvh_emit', group: 'bvhBuild' },
  bvhSummary: { module: 'package::accel::gpu_build::lbvh_summary', group: 'bvhBuild' },
  bvhRefit: { module: 'package::accel::gpu_build::refit', group: 'bvhBuild' },
  oidnConv: { module: 'package::film::denoise::oidn::conv', group: 'oidn' },
  oidnConvF16: { module: 'package::film::denoise::oidn::conv', group: 'oidn', conditions: { f16: true } },
  oidnExposure: { module: 'package::film::denoise::oidn::exposure', group: 'oidn' },
  oidnInput: { module: 'package::film::denoise::oidn::input', group: 'oidn' },
  oidnInputF16: { module: 'package::film::denoise::oidn::input', group: 'oidn', conditions: { f16: true } },
  oidnOutput: { module: 'package::film::denoise::oidn::output', group: 'oidn' },
  oidnOutputF16: { module: 'package::film::denoise::oidn::output', group: 'oidn', conditions: { f16: true } },
  // The raster renderer (src/raster/): forward shading and its passes, skinning, environment
  // precomputation and the output resolve, each binding set sharing its bind group layouts.
  rasterForward: { module: 'package::raster::shaders::forward', group: 'raster', set: 'draw' },
  rasterShadow: { module: 'package::raster::shaders::shadow', group: 'raster', set: 'draw' },
  rasterBackground: { module: 'package::raster::shaders::background', group: 'raster', set: 'draw' },
  rasterSkin: { module: 'package::raster::shaders::skin', group: 'raster', set: 'skin' },
  rasterIblDownsample: { module: 'package::raster::shaders::ibl_downsample', group: 'raster', set: 'ibl' },
  rasterIblPrefilter: { module: 'package::raster::shaders::ibl_prefilter', group: 'raster', set: 'ibl' },
  rasterIblIrradiance: { module: 'package::raster::shaders::ibl_irradiance', group: 'raster', set: 'ibl' },
  rasterBrdfLut: { module: 'package::raster::shaders::brdf_lut', group: 'raster', set: 'ibl' },
  rasterResolve: { module: 'package::raster::shaders::resolve', group: 'raster', set: 'resolve' },
} as const satisfies Record<string, ProgramSpec>;

export type ProgramName = keyof typeof programSpecs;

/** The programs of the groups createWavefrontPathTracingComputeShaderSource() returns. */
export type ShaderSourceProgramName = { [K in ProgramName]: (typeof programGroups)[(typeof programSpecs)[K]['group']]['shaderSource'] extends true ? K : never }[ProgramName];
