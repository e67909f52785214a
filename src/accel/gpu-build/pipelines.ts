/**
 * Compute pipelines of the GPU BVH builder and refitter, compiled once per device, with explicit
 * layouts derived from the bindings each program declares (src/shaders/program-pipelines.ts).
 */
import { GpuRendererError } from '../../errors/gpu-renderer-error.ts';
import { computePipeline, type KernelPipeline } from '../../shaders/program-pipelines.ts';
import { allShaderFeatures } from '../../shaders/features.ts';
import { bvhBuildBindings } from './bindings.ts';
import type { ProgramName } from '../../shaders/programs.ts';

export const bvhBuildKernels = {
  centroidBounds: ['bvhMorton', 'centroid_bounds'],
  mortonSchedule: ['bvhMorton', 'morton_schedule'],
  mortonCodes: ['bvhMorton', 'morton_codes'],
  sortCount: ['bvhSort', 'sort_count'],
  sortScatter: ['bvhSort', 'sort_scatter'],
  scanBlocks: ['bvhScan', 'scan_blocks'],
  scanAdd: ['bvhScan', 'scan_add'],
  hierarchy: ['bvhHierarchy', 'lbvh_hierarchy'],
  gather: ['bvhGather', 'gather_primitives'],
  fit: ['bvhFit', 'lbvh_fit'],
  markKept: ['bvhFit', 'mark_kept'],
  emitNodes: ['bvhEmit', 'emit_nodes'],
  writeSummary: ['bvhSummary', 'write_summary'],
  refitReset: ['bvhRefit', 'refit_reset'],
  refitNodes: ['bvhRefit', 'refit_nodes'],
} as const satisfies Record<string, readonly [ProgramName, string]>;

export type BvhBuildKernel = keyof typeof bvhBuildKernels;
export type BvhBuildPipelines = Record<BvhBuildKernel, KernelPipeline>;

const cache = new WeakMap<GPUDevice, Promise<BvhBuildPipelines>>();

async function create(device: GPUDevice): Promise<BvhBuildPipelines> {
  device.pushErrorScope('validation');
  let pipelines: BvhBuildPipelines | undefined;
  let failure: unknown;
  try {
    const entries = await Promise.all(
      Object.entries(bvhBuildKernels).map(async ([name, [program, entry]]) => [name, await computePipeline(device, bvhBuildBindings, program, entry, allShaderFeatures)] as const),
    );
    pipelines = Object.fromEntries(entries) as BvhBuildPipelines;
  } catch (error) {
    failure = error;
  }
  const validation = await device.popErrorScope();
  if (failure !== undefined) throw failure;
  if (validation) throw new GpuRendererError('GPU_VALIDATION_FAILED', `BVH build pipeline creation failed: ${validation.message}`);
  return pipelines!;
}

/** The builder's pipelines for `device`, created on first use. */
export function bvhBuildPipelines(device: GPUDevice): Promise<BvhBuildPipelines> {
  let p = cache.get(device);
  if (!p) {
    p = create(device);
    p.catch(() => cache.delete(device));
    cache.set(device, p);
  }
  return p;
}
