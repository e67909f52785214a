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
  readonly bindings: 'pathTracer' | 'display';
}

export const programSpecs = {
  camera: { module: 'package::pathtracer::kernels::camera', bindings: 'pathTracer' },
  trace: { module: 'package::pathtracer::kernels::trace', bindings: 'pathTracer' },
  shade: { module: 'package::pathtracer::kernels::shade', bindings: 'pathTracer' },
  accumulate: { module: 'package::pathtracer::kernels::accumulate', bindings: 'pathTracer' },
  adaptiveSampling: { module: 'package::pathtracer::adaptive_sampling', bindings: 'pathTracer' },
  denoiseInput: { module: 'package::pathtracer::denoise_input', bindings: 'pathTracer' },
  denoise: { module: 'package::post::denoise::atrous', bindings: 'pathTracer' },
  resolve: { module: 'package::post::display::resolve', bindings: 'display' },
  present: { module: 'package::post::display::present', bindings: 'display' },
} as const satisfies Record<string, ProgramSpec>;

export type ProgramName = keyof typeof programSpecs;
