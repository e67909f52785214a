import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { pathTracerBindings } from '../gpu-layout/bindings.ts';
import { displayBindings } from '../shaders/display-bindings.ts';
import type { ShaderFeatures } from '../shaders/features.ts';
import { computePipeline, type KernelPipeline } from '../shaders/program-pipelines.ts';
import type { ProgramName } from '../shaders/programs.ts';

/** The compute kernels of one wavefront wave, with the program and entry point of each. */
export const wavefrontKernels = {
  camera: { program: 'camera', entryPoint: 'generate_camera_rays' },
  trace: { program: 'trace', entryPoint: 'trace_rays' },
  shade: { program: 'shade', entryPoint: 'shade_hits' },
  accumulate: { program: 'accumulate', entryPoint: 'accumulate_samples' },
} as const satisfies Record<string, { program: ProgramName; entryPoint: string }>;

export type WavefrontKernelName = keyof typeof wavefrontKernels;

export interface PathTracerPipelines {
  kernels: Record<WavefrontKernelName, KernelPipeline>;
  resolve: KernelPipeline;
}

const pipelineCache = new WeakMap<GPUDevice, Map<string, Promise<PathTracerPipelines>>>();

export function featureKey(features: ShaderFeatures): string {
  return Object.entries(features).map(([k, v]) => `${k}=${v ? 1 : 0}`).join(',');
}

async function createPipelines(device: GPUDevice, features: ShaderFeatures): Promise<PathTracerPipelines> {
  device.pushErrorScope('validation');
  let pipelines: PathTracerPipelines | undefined;
  let failure: unknown;
  try {
    const entries = await Promise.all(
      (Object.entries(wavefrontKernels) as [WavefrontKernelName, (typeof wavefrontKernels)[WavefrontKernelName]][]).map(
        async ([name, k]) => [name, await computePipeline(device, pathTracerBindings, k.program, k.entryPoint, features)] as const,
      ),
    );
    const resolve = await computePipeline(device, displayBindings, 'resolve', 'resolve_pixels', features);
    pipelines = { kernels: Object.fromEntries(entries) as Record<WavefrontKernelName, KernelPipeline>, resolve };
  } catch (error) {
    failure = error;
  }
  // The scope is popped whatever happened, so a failed creation leaves the device's scopes balanced.
  const validation = await device.popErrorScope();
  if (failure !== undefined) throw failure;
  if (validation) throw new GpuRendererError('GPU_VALIDATION_FAILED', `pipeline creation failed: ${validation.message}`);
  return pipelines!;
}

/** The path tracer's pipelines for a feature set, created once per device and feature set. */
export function pathTracerPipelines(device: GPUDevice, features: ShaderFeatures): Promise<PathTracerPipelines> {
  let perDevice = pipelineCache.get(device);
  if (!perDevice) pipelineCache.set(device, (perDevice = new Map()));
  const key = featureKey(features);
  let p = perDevice.get(key);
  if (!p) {
    p = createPipelines(device, features);
    p.catch(() => perDevice.delete(key));
    perDevice.set(key, p);
  }
  return p;
}

