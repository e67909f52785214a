import { pathTracerBindings } from '../gpu-layout/bindings.ts';
import type { KernelPipeline } from '../shaders/program-pipelines.ts';
import { createProgramBindGroups, dynamicSizes, type PathTracerResourceMap } from '../shaders/program-bind-groups.ts';
import type { IntegratorKernelSet, WavefrontKernelName } from './pipelines.ts';

export type { PathTracerResourceMap };

export interface KernelBindGroups {
  pipeline: GPUComputePipeline;
  /** Bind groups by group index. */
  groups: GPUBindGroup[];
  /** The dynamic-offset bindings of each group, in binding order (what setBindGroup's offsets follow). */
  dynamic: string[][];
}


export function createKernelBindGroups(device: GPUDevice, kernels: IntegratorKernelSet<KernelPipeline>, resources: PathTracerResourceMap): IntegratorKernelSet<KernelBindGroups> {
  const bindingOf = (name: string): number => pathTracerBindings[name as keyof typeof pathTracerBindings].binding;
  const out: IntegratorKernelSet<KernelBindGroups> = {};
  for (const [name, k] of Object.entries(kernels) as [WavefrontKernelName, KernelPipeline][]) {
    out[name] = {
      pipeline: k.pipeline,
      groups: createProgramBindGroups(device, k, resources, bindingOf, name),
      dynamic: k.bindingsByGroup.map((group) => group.filter((n) => dynamicSizes[n] !== undefined).sort((a, b) => bindingOf(a) - bindingOf(b))),
    };
  }
  return out;
}
