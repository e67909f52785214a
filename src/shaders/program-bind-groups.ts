// Bind groups for a program's reflected layouts, from a binding name -> GPU resource map; shared by
// the path tracer's kernels, the film's passes and the BVH builder.
import { bounceUniformsLayout, waveUniformsLayout } from '../gpu-layout/records.ts';
import type { ProgramLayout } from './program-pipelines.ts';

/** The GPU resource behind every binding name of the path tracer. */
export type PathTracerResourceMap = Record<string, GPUBuffer | GPUTextureView>;

/** Sizes of the dynamic-offset uniform windows (one record each). */
export const dynamicSizes: Record<string, number> = { wave: waveUniformsLayout.size, bounce: bounceUniformsLayout.size };

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
