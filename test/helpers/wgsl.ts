// Test kernels written in WESL against the package's own modules: a test's root module imports
// what it exercises (`import package::materials::gltf_bsdf;`), is linked with the same linker and
// sources as the shipped programs, and runs on real WebGPU with an automatic pipeline layout.
import { linkProgram, weslProjectSources } from '../../scripts/shader-build/wesl-project.ts';
import { reflectProgram, type ProgramReflection } from '../../scripts/shader-build/reflect.ts';
import type { WeslSources } from '../../scripts/shader-build/layout-modules.ts';
import { createShaderChecked } from './gpu.ts';

let projectSources: WeslSources | undefined;

export interface LinkedTestProgram {
  wgsl: string;
  reflection: ProgramReflection;
}

/** Links `source` (a WESL root module) against the package's modules. */
export async function linkTestProgram(source: string): Promise<LinkedTestProgram> {
  projectSources ??= weslProjectSources();
  const linked = await linkProgram('package::test_root', { 'test_root.wesl': source }, projectSources);
  const wgsl = linked.dest;
  return { wgsl, reflection: reflectProgram(wgsl, 'test_root') };
}

export type TestResource = GPUBuffer | GPUTextureView | GPUSampler;

export interface TestDispatch {
  source: string;
  entryPoint?: string;
  /** Resource for every binding the linked program declares, by name. */
  resources: Record<string, TestResource>;
  workgroups: number | [number, number, number];
  constants?: Record<string, number>;
}

function bindingResource(r: TestResource): GPUBindingResource {
  return 'mapAsync' in r ? { buffer: r } : r;
}

/** Links, compiles (throwing on WGSL errors) and dispatches a test kernel, then waits for the GPU. */
export async function runTestProgram(device: GPUDevice, d: TestDispatch): Promise<LinkedTestProgram> {
  const program = await linkTestProgram(d.source);
  const module = await createShaderChecked(device, program.wgsl);
  device.pushErrorScope('validation');
  const pipeline = await device.createComputePipelineAsync({
    layout: 'auto',
    compute: { module, entryPoint: d.entryPoint ?? 'main', ...(d.constants ? { constants: d.constants } : {}) },
  });
  const groups = [...new Set(program.reflection.bindings.map((b) => b.group))].sort();
  const encoder = device.createCommandEncoder();
  const pass = encoder.beginComputePass();
  pass.setPipeline(pipeline);
  for (const g of groups) {
    const entries = program.reflection.bindings
      .filter((b) => b.group === g)
      .map((b) => {
        const resource = d.resources[b.name];
        if (!resource) throw new Error(`test kernel uses binding ${b.name} but no resource was given`);
        return { binding: b.binding, resource: bindingResource(resource) };
      });
    pass.setBindGroup(g, device.createBindGroup({ layout: pipeline.getBindGroupLayout(g), entries }));
  }
  const [x, y, z] = typeof d.workgroups === 'number' ? [d.workgroups, 1, 1] : d.workgroups;
  pass.dispatchWorkgroups(x, y, z);
  pass.end();
  device.queue.submit([encoder.finish()]);
  const error = await device.popErrorScope();
  if (error) throw new Error(error.message);
  await device.queue.onSubmittedWorkDone();
  return program;
}
