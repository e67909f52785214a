/**
 * The GPU-program layer every renderer builds on (the path tracer, its BVH builder and denoisers,
 * the raster renderer): bind group layouts from a program's reflected bindings and its group's
 * binding table, shader modules compiled once per device with WGSL errors turned into typed errors,
 * override constants from the shader features, and compute pipelines from those. The layer sits
 * below the code that owns each binding table, so callers hand it theirs.
 */
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { bindingLayoutEntry, type BindingSpec } from '../gpu-layout/bindings.ts';
import { ShaderStage } from '../gpu/webgpu-constants.ts';
import type { ShaderFeatures } from './features.ts';
import { generatedPrograms } from './programs.generated.ts';
import { programWgsl } from './program-wgsl.ts';
import { programSpecs, type ProgramName } from './programs.ts';

/** A program group's binding table (gpu-layout/bindings.ts and its peers), by binding name. */
export type BindingTable = Readonly<Record<string, BindingSpec>>;

export interface ProgramLayout {
  /** Bind group layouts by group index (empty layouts fill unused lower groups). */
  groups: GPUBindGroupLayout[];
  /** The bindings of each group, by group index. */
  bindingsByGroup: string[][];
  layout: GPUPipelineLayout;
}

export interface KernelPipeline extends ProgramLayout {
  pipeline: GPUComputePipeline;
}

/**
 * Explicit bind group layouts for `bindings` of the program's binding table `table`: by default
 * exactly the bindings its linked WGSL declares (reflected at build time, checked against the
 * table there). Programs that share bind groups (a raster binding set) pass the bindings they share
 * instead. `visibility` applies to the bindings whose table entry names no stages.
 */
export function programLayout(
  device: GPUDevice,
  table: BindingTable,
  program: ProgramName,
  visibility: number = ShaderStage.COMPUTE,
  bindings: readonly string[] = generatedPrograms[program].bindings,
): ProgramLayout {
  const byGroup: string[][] = [];
  for (const name of bindings) {
    const spec = table[name];
    if (spec === undefined) throw new Error(`program ${program} (group ${programSpecs[program].group}): binding ${name} is not in the table it was given`);
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

/** A compute pipeline of one entry point of a program, on its reflected layout. */
export async function computePipeline(device: GPUDevice, table: BindingTable, program: ProgramName, entryPoint: string, features: ShaderFeatures): Promise<KernelPipeline> {
  const layout = programLayout(device, table, program);
  const module = await programModule(device, program);
  const pipeline = await device.createComputePipelineAsync({
    label: `${program}.${entryPoint}`,
    layout: layout.layout,
    compute: { module, entryPoint, constants: overrideConstants(program, features) },
  });
  return { ...layout, pipeline };
}
