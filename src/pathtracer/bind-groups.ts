import { pathTracerBindings } from '../gpu-layout/bindings.ts';
import { bounceUniformsLayout, waveUniformsLayout } from '../gpu-layout/records.ts';
import type { KernelPipeline, ProgramLayout } from '../shaders/program-pipelines.ts';
import type { WavefrontKernelName } from './pipelines.ts';

/** The GPU resource behind every binding name of the path tracer. */
export type PathTracerResourceMap = Record<string, GPUBuffer | GPUTextureView>;

/** Sizes of the dynamic-offset uniform windows (one record each). */
const dynamicSizes: Record<string, number> = { wave: waveUniformsLayout.size, bounce: bounceUniformsLayout.size };

export interface KernelBindGroups {
  pipeline: GPUComputePipeline;
  /** Bind groups by group index. */
  groups: GPUBindGroup[];
  /** The dynamic-offset bindings of each group, in binding order (what setBindGroup's offsets follow). */
  dynamic: string[][];
}

function resourceOf(resources: PathTracerResourceMap, name: string): GPUBindingResource {
  const r = resources[name];
  if (!r) throw new Error(`no resource for binding ${name}`);
  if ('mapAsync' in r) return dynamicSizes[name] !== undefined ? { buffer: r, size: dynamicSizes[name] } : { buffer: r };
  return r;
}

/** Bind groups matching a program's explicit layouts, from a name -> resource map. */
export function createProgramBindGroups(device: GPUDevice, layout: ProgramLayout, resources: PathTracerResourceMap, bindingOf: (name: string) => number, label: string): GPUBindGroup[] {
  return layout.groups.map((groupLayout, g) =>
    device.createBindGroup({
      label: `${label}.group${g}`,
      layout: groupLayout,
      entries: layout.bindingsByGroup[g]!.map((name) => ({ binding: bindingOf(name), resource: resourceOf(resources, name) })),
    }),
  );
}

export function createKernelBindGroups(device: GPUDevice, kernels: Record<WavefrontKernelName, KernelPipeline>, resources: PathTracerResourceMap): Record<WavefrontKernelName, KernelBindGroups> {
  const bindingOf = (name: string): number => pathTracerBindings[name as keyof typeof pathTracerBindings].binding;
  const out = {} as Record<WavefrontKernelName, KernelBindGroups>;
  for (const [name, k] of Object.entries(kernels) as [WavefrontKernelName, KernelPipeline][]) {
    out[name] = {
      pipeline: k.pipeline,
      groups: createProgramBindGroups(device, k, resources, bindingOf, name),
      dynamic: k.bindingsByGroup.map((group) => group.filter((n) => dynamicSizes[n] !== undefined).sort((a, b) => bindingOf(a) - bindingOf(b))),
    };
  }
  return out;
}
