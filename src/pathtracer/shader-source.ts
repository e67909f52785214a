import { generatedPrograms } from '../shaders/programs.generated.ts';
import type { ProgramName } from '../shaders/programs.ts';

export type WavefrontShaderSources = Record<ProgramName, string>;

/**
 * The linked WGSL of every GPU program (the wavefront kernels, the display resolve and the canvas
 * present), as the build's WESL linker produced them from src/**\/*.wesl.
 */
export function createWavefrontPathTracingComputeShaderSource(): WavefrontShaderSources {
  return Object.fromEntries(Object.entries(generatedPrograms).map(([name, p]) => [name, p.wgsl])) as WavefrontShaderSources;
}
