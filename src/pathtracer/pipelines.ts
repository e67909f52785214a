import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { pathTracerBindings } from '../gpu-layout/bindings.ts';
import { displayBindings } from '../shaders/display-bindings.ts';
import type { ShaderFeatures } from '../shaders/features.ts';
import { computePipeline, type KernelPipeline } from '../shaders/program-pipelines.ts';
import { generatedPrograms } from '../shaders/programs.generated.ts';
import type { ProgramName } from '../shaders/programs.ts';
import type { PathTracingIntegrator } from './types.ts';

/** The compute kernels of a wave, with the program and entry point of each. */
export const wavefrontKernels = {
  camera: { program: 'camera', entryPoint: 'generate_camera_rays' },
  trace: { program: 'trace', entryPoint: 'trace_rays' },
  shadingSize: { program: 'shadingSize', entryPoint: 'size_shading' },
  shade: { program: 'shade', entryPoint: 'shade_hits' },
  accumulate: { program: 'accumulate', entryPoint: 'accumulate_samples' },
  megakernel: { program: 'megakernel', entryPoint: 'trace_paths' },
} as const satisfies Record<string, { program: ProgramName; entryPoint: string }>;

export type WavefrontKernelName = keyof typeof wavefrontKernels;

/** The kernels each integrator dispatches (only those are compiled). */
export const integratorKernels = {
  wavefront: ['camera', 'trace', 'shadingSize', 'shade', 'accumulate'],
  megakernel: ['megakernel', 'accumulate'],
} as const satisfies Record<PathTracingIntegrator, readonly WavefrontKernelName[]>;

/** Pipelines or bind groups of the kernels an integrator dispatches. */
export type IntegratorKernelSet<T> = Partial<Record<WavefrontKernelName, T>>;

export interface PathTracerPipelines {
  kernels: IntegratorKernelSet<KernelPipeline>;
  resolve: KernelPipeline;
}

/** Storage buffers a path tracer program binds in its one (compute) stage. */
function storageBufferCount(program: ProgramName): number {
  return generatedPrograms[program].bindings.filter((name) => pathTracerBindings[name as keyof typeof pathTracerBindings].kind === 'storage').length;
}

/** The most storage buffers one kernel of an integrator binds in its one (compute) stage. */
export function integratorStorageBuffers(integrator: PathTracingIntegrator): number {
  return Math.max(...integratorKernels[integrator].map((name) => storageBufferCount(wavefrontKernels[name].program)));
}

/** The integrator a renderer runs, and why it is not the one asked for (null when it is). */
export interface IntegratorChoice {
  integrator: PathTracingIntegrator;
  warning: string | null;
}

/**
 * The integrator that runs on a device: the one requested where the device offers the storage
 * buffers per stage its kernels bind, else the default wavefront, which binds fewer (WebGPU's
 * guaranteed 8) and computes the same image. Only a device too small for the wavefront too is
 * refused, with INVALID_OPTION naming `integrator`.
 */
export function chooseIntegrator(requested: PathTracingIntegrator, limits: GPUSupportedLimits): IntegratorChoice {
  const offered = limits.maxStorageBuffersPerShaderStage;
  const needed = integratorStorageBuffers(requested);
  if (needed <= offered) return { integrator: requested, warning: null };
  const fallback: PathTracingIntegrator = 'wavefront';
  const fallbackNeeds = integratorStorageBuffers(fallback);
  if (requested === fallback || fallbackNeeds > offered) {
    throw new GpuRendererError(
      'INVALID_OPTION',
      `the ${requested} integrator binds ${needed} storage buffers in one kernel; the device offers ${offered} per shader stage (request a device with maxStorageBuffersPerShaderStage >= ${Math.min(needed, fallbackNeeds)})`,
      { field: 'integrator' },
    );
  }
  return {
    integrator: fallback,
    warning: `integrator: the ${requested} integrator binds ${needed} storage buffers in one kernel; the device offers ${offered} per shader stage (maxStorageBuffersPerShaderStage), so the ${fallback} integrator runs instead (the same image; request a device with maxStorageBuffersPerShaderStage >= ${needed} for the ${requested})`,
  };
}

const pipelineCache = new WeakMap<GPUDevice, Map<string, Promise<PathTracerPipelines>>>();

export function featureKey(features: ShaderFeatures): string {
  return Object.entries(features).map(([k, v]) => `${k}=${v ? 1 : 0}`).join(',');
}

async function createPipelines(device: GPUDevice, features: ShaderFeatures, integrator: PathTracingIntegrator): Promise<PathTracerPipelines> {
  device.pushErrorScope('validation');
  let pipelines: PathTracerPipelines | undefined;
  let failure: unknown;
  try {
    const entries = await Promise.all(
      integratorKernels[integrator].map(async (name) => {
        const k = wavefrontKernels[name];
        return [name, await computePipeline(device, pathTracerBindings, k.program, k.entryPoint, features)] as const;
      }),
    );
    const resolve = await computePipeline(device, displayBindings, 'resolve', 'resolve_pixels', features);
    pipelines = { kernels: Object.fromEntries(entries) as IntegratorKernelSet<KernelPipeline>, resolve };
  } catch (error) {
    failure = error;
  }
  // The scope is popped whatever happened, so a failed creation leaves the device's scopes balanced.
  const validation = await device.popErrorScope();
  if (failure !== undefined) throw failure;
  if (validation) throw new GpuRendererError('GPU_VALIDATION_FAILED', `pipeline creation failed: ${validation.message}`);
  return pipelines!;
}

/** The path tracer's pipelines for a feature set and integrator, created once per device and both. */
export function pathTracerPipelines(device: GPUDevice, features: ShaderFeatures, integrator: PathTracingIntegrator = 'wavefront'): Promise<PathTracerPipelines> {
  let perDevice = pipelineCache.get(device);
  if (!perDevice) pipelineCache.set(device, (perDevice = new Map()));
  const key = `${integrator}:${featureKey(features)}`;
  let p = perDevice.get(key);
  if (!p) {
    p = createPipelines(device, features, integrator);
    p.catch(() => perDevice.delete(key));
    perDevice.set(key, p);
  }
  return p;
}

