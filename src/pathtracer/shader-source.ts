import { composeShader } from '../shaders/modules.ts';
import { wavefrontKernels, type WavefrontKernelName } from './kernels.ts';

export type WavefrontShaderSources = Record<WavefrontKernelName | 'resolve' | 'present', string>;

/**
 * The composed WGSL of every wavefront kernel (each a separate program, so a pipeline only sees the
 * bindings it uses), plus the display resolve and canvas present programs.
 */
export function createWavefrontPathTracingComputeShaderSource(): WavefrontShaderSources {
  const out: Partial<WavefrontShaderSources> = {};
  for (const [name, spec] of Object.entries(wavefrontKernels) as [WavefrontKernelName, (typeof wavefrontKernels)[WavefrontKernelName]][]) {
    out[name] = composeShader([spec.module]);
  }
  out.resolve = composeShader(['kernel-resolve']);
  out.present = composeShader(['kernel-present']);
  return out as WavefrontShaderSources;
}
