import { shaderSourceWgsl } from '../shaders/shader-source.generated.ts';
import type { ShaderSourceProgramName } from '../shaders/programs.ts';

export type WavefrontShaderSources = Record<ShaderSourceProgramName, string>;

/**
 * The linked WGSL of the path tracer's programs, as the build's WESL linker produced them from
 * src/**\/*.wesl: the wavefront kernels (camera, trace, shade, accumulate), adaptive sampling, the
 * à-trous denoiser, the display resolve and the canvas present. The GPU BVH builder's and the OIDN
 * denoiser's programs are not included: they ship in chunks of their own that the renderer loads
 * when it first uses them.
 */
export function createWavefrontPathTracingComputeShaderSource(): WavefrontShaderSources {
  return { ...shaderSourceWgsl };
}
