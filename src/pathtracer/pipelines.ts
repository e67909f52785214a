import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { ShaderStage } from '../gpu/webgpu-constants.ts';
import { bindGroupLayoutEntries, kernelGroups, wavefrontKernels, type WavefrontKernelName } from './kernels.ts';
import type { WavefrontShaderSources } from './shader-source.ts';

export interface WavefrontKernelPipeline {
  pipeline: GPUComputePipeline;
  /** Bind group layout per group index. */
  groupLayouts: GPUBindGroupLayout[];
}

export interface WavefrontPipelines {
  kernels: Record<WavefrontKernelName, WavefrontKernelPipeline>;
  resolve: GPUComputePipeline;
  resolveLayout: GPUBindGroupLayout;
}

async function checkedModule(device: GPUDevice, code: string, label: string): Promise<GPUShaderModule> {
  const module = device.createShaderModule({ code, label });
  const info = await module.getCompilationInfo();
  const errors = info.messages.filter((m) => m.type === 'error');
  if (errors.length > 0) {
    const lines = code.split('\n');
    const detail = errors.map((e) => `${label}:${e.lineNum}:${e.linePos} ${e.message} | ${lines[e.lineNum - 1]?.trim() ?? ''}`).join('\n');
    throw new GpuRendererError('SHADER_COMPILATION_FAILED', `WGSL compilation failed:\n${detail}`);
  }
  return module;
}

/** Compiles every kernel with an explicit pipeline layout built from its binding list. */
export async function createWavefrontPipelines(device: GPUDevice, sources: WavefrontShaderSources): Promise<WavefrontPipelines> {
  device.pushErrorScope('validation');
  const kernels = {} as Record<WavefrontKernelName, WavefrontKernelPipeline>;
  const modules = new Map<string, GPUShaderModule>();
  for (const [name, spec] of Object.entries(wavefrontKernels) as [WavefrontKernelName, (typeof wavefrontKernels)[WavefrontKernelName]][]) {
    const code = sources[name];
    let module = modules.get(code);
    if (!module) {
      module = await checkedModule(device, code, spec.module);
      modules.set(code, module);
    }
    const groupLayouts = kernelGroups(spec).map((g) => device.createBindGroupLayout({ label: `${name}.group${g}`, entries: bindGroupLayoutEntries(spec, g) }));
    const pipeline = await device.createComputePipelineAsync({
      label: name,
      layout: device.createPipelineLayout({ bindGroupLayouts: groupLayouts }),
      compute: { module, entryPoint: spec.entryPoint },
    });
    kernels[name] = { pipeline, groupLayouts };
  }
  const resolveModule = await checkedModule(device, sources.resolve, 'kernel-resolve');
  const resolveLayout = device.createBindGroupLayout({
    label: 'resolve',
    entries: [
      { binding: 0, visibility: ShaderStage.COMPUTE, buffer: { type: 'uniform' } },
      { binding: 1, visibility: ShaderStage.COMPUTE, buffer: { type: 'read-only-storage' } },
      { binding: 2, visibility: ShaderStage.COMPUTE, buffer: { type: 'storage' } },
    ],
  });
  const resolve = await device.createComputePipelineAsync({
    label: 'resolve',
    layout: device.createPipelineLayout({ bindGroupLayouts: [resolveLayout] }),
    compute: { module: resolveModule, entryPoint: 'resolve_pixels' },
  });
  const error = await device.popErrorScope();
  if (error) throw new GpuRendererError('GPU_VALIDATION_FAILED', `pipeline creation failed: ${error.message}`);
  return { kernels, resolve, resolveLayout };
}

/** Render pipeline drawing the resolve into a canvas texture of `format`. */
export async function createPresentPipeline(device: GPUDevice, code: string, format: GPUTextureFormat): Promise<{ pipeline: GPURenderPipeline; layout: GPUBindGroupLayout }> {
  const module = await checkedModule(device, code, 'kernel-present');
  const layout = device.createBindGroupLayout({
    label: 'present',
    entries: [
      { binding: 0, visibility: ShaderStage.FRAGMENT, buffer: { type: 'uniform' } },
      { binding: 1, visibility: ShaderStage.FRAGMENT, buffer: { type: 'read-only-storage' } },
    ],
  });
  const pipeline = await device.createRenderPipelineAsync({
    label: 'present',
    layout: device.createPipelineLayout({ bindGroupLayouts: [layout] }),
    vertex: { module, entryPoint: 'present_vertex' },
    fragment: { module, entryPoint: 'present_fragment', targets: [{ format }] },
    primitive: { topology: 'triangle-list' },
  });
  return { pipeline, layout };
}
