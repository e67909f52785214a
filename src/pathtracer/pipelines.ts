import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { bindingLayoutEntry, pathTracerBindings, type BindingSpec } from '../gpu-layout/bindings.ts';
import { ShaderStage } from '../gpu/webgpu-constants.ts';
import { oidnBindings } from '../post/denoise/oidn/bindings.ts';
import { displayBindings } from '../shaders/display-bindings.ts';
import { bvhBuildBindings } from '../accel/gpu-build/bindings.ts';
import type { ShaderFeatures } from '../shaders/features.ts';
import { generatedPrograms } from '../shaders/programs.generated.ts';
import { programWgsl } from '../shaders/program-wgsl.ts';
import { programSpecs, type ProgramGroupName, type ProgramName } from '../shaders/programs.ts';

/** The compute kernels of one wavefront wave, with the program and entry point of each. */
export const wavefrontKernels = {
  camera: { program: 'camera', entryPoint: 'generate_camera_rays' },
  trace: { program: 'trace', entryPoint: 'trace_rays' },
  shade: { program: 'shade', entryPoint: 'shade_hits' },
  accumulate: { program: 'accumulate', entryPoint: 'accumulate_samples' },
} as const satisfies Record<string, { program: ProgramName; entryPoint: string }>;

export type WavefrontKernelName = keyof typeof wavefrontKernels;

export interface ProgramLayout {
  /** Bind group layouts by group index (empty layouts fill unused lower groups). */
  groups: GPUBindGroupLayout[];
  /** The program's bindings, by group index. */
  bindingsByGroup: string[][];
  layout: GPUPipelineLayout;
}

export interface KernelPipeline extends ProgramLayout {
  pipeline: GPUComputePipeline;
}

export interface PathTracerPipelines {
  kernels: Record<WavefrontKernelName, KernelPipeline>;
  resolve: KernelPipeline;
}

const tables: Record<ProgramGroupName, Record<string, BindingSpec>> = { pathTracer: pathTracerBindings, display: displayBindings, bvhBuild: bvhBuildBindings, oidn: oidnBindings };

/** Explicit bind group layouts for exactly the bindings a program's linked WGSL declares. */
export function programLayout(device: GPUDevice, program: ProgramName, visibility: number = ShaderStage.COMPUTE): ProgramLayout {
  const table = tables[programSpecs[program].group];
  const names = generatedPrograms[program].bindings;
  const byGroup: string[][] = [];
  for (const name of names) {
    const spec = table[name]!;
    (byGroup[spec.group] ??= []).push(name);
  }
  for (let g = 0; g < byGroup.length; g++) byGroup[g] ??= [];
  const groups = byGroup.map((group, g) =>
    device.createBindGroupLayout({
      label: `${program}.group${g}`,
      entries: group.map((name) => bindingLayoutEntry(table[name]!, visibility)).sort((a, b) => a.binding - b.binding),
    }),
  );
  return { groups, bindingsByGroup: byGroup, layout: device.createPipelineLayout({ label: program, bindGroupLayouts: groups }) };
}

const modules = new WeakMap<GPUDevice, Map<ProgramName, Promise<GPUShaderModule>>>();

/** The program's shader module, compiled once per device; WGSL errors become typed errors. */
export function programModule(device: GPUDevice, program: ProgramName): Promise<GPUShaderModule> {
  let perDevice = modules.get(device);
  if (!perDevice) modules.set(device, (perDevice = new Map()));
  let module = perDevice.get(program);
  if (!module) {
    module = (async () => {
      const code = await programWgsl(program);
      const m = device.createShaderModule({ code, label: program });
      const info = await m.getCompilationInfo();
      const errors = info.messages.filter((e) => e.type === 'error');
      if (errors.length > 0) {
        const lines = code.split('\n');
        const detail = errors.map((e) => `${program}:${e.lineNum}:${e.linePos} ${e.message} | ${lines[e.lineNum - 1]?.trim() ?? ''}`).join('\n');
        throw new GpuRendererError('SHADER_COMPILATION_FAILED', `WGSL compilation failed:\n${detail}`);
      }
      return m;
    })();
    module.catch(() => perDevice.delete(program));
    perDevice.set(program, module);
  }
  return module;
}

/** The override constants a program declares, from the feature set. */
export function overrideConstants(program: ProgramName, features: ShaderFeatures): Record<string, number> {
  const out: Record<string, number> = {};
  for (const name of generatedPrograms[program].overrides) {
    if (!(name in features)) throw new Error(`program ${program} declares override ${name}, which is no shader feature`);
    out[name] = features[name as keyof ShaderFeatures] ? 1 : 0;
  }
  return out;
}

const pipelineCache = new WeakMap<GPUDevice, Map<string, Promise<PathTracerPipelines>>>();

export function featureKey(features: ShaderFeatures): string {
  return Object.entries(features).map(([k, v]) => `${k}=${v ? 1 : 0}`).join(',');
}

export async function computePipeline(device: GPUDevice, program: ProgramName, entryPoint: string, features: ShaderFeatures): Promise<KernelPipeline> {
  const layout = programLayout(device, program);
  const module = await programModule(device, program);
  const pipeline = await device.createComputePipelineAsync({
    label: `${program}.${entryPoint}`,
    layout: layout.layout,
    compute: { module, entryPoint, constants: overrideConstants(program, features) },
  });
  return { ...layout, pipeline };
}

async function createPipelines(device: GPUDevice, features: ShaderFeatures): Promise<PathTracerPipelines> {
  device.pushErrorScope('validation');
  let pipelines: PathTracerPipelines | undefined;
  let failure: unknown;
  try {
    const entries = await Promise.all(
      (Object.entries(wavefrontKernels) as [WavefrontKernelName, (typeof wavefrontKernels)[WavefrontKernelName]][]).map(
        async ([name, k]) => [name, await computePipeline(device, k.program, k.entryPoint, features)] as const,
      ),
    );
    const resolve = await computePipeline(device, 'resolve', 'resolve_pixels', features);
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

/** Render pipeline drawing the display resolve into a canvas texture of `format`. */
export async function createPresentPipeline(device: GPUDevice, format: GPUTextureFormat): Promise<{ pipeline: GPURenderPipeline; layout: ProgramLayout }> {
  const layout = programLayout(device, 'present', ShaderStage.FRAGMENT);
  const module = await programModule(device, 'present');
  const pipeline = await device.createRenderPipelineAsync({
    label: 'present',
    layout: layout.layout,
    vertex: { module, entryPoint: 'present_vertex' },
    fragment: { module, entryPoint: 'present_fragment', targets: [{ format }] },
    primitive: { topology: 'triangle-list' },
  });
  return { pipeline, layout };
}
