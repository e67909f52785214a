import { ShaderStage } from '../gpu/webgpu-constants.ts';

/**
 * The wavefront kernels and the exact bindings each one uses. Pipeline layouts and bind groups are
 * built from these lists, so every kernel stays within WebGPU's baseline of 8 storage buffers per
 * stage and never binds the indirect-argument buffer it is dispatched with.
 */
export type WavefrontBindingName =
  | 'frame'
  | 'triangles'
  | 'triangleAttributes'
  | 'bvhNodes'
  | 'materials'
  | 'sceneObjects'
  | 'lights'
  | 'paths'
  | 'shadowRays'
  | 'counters'
  | 'tileRadiance'
  | 'accumulation'
  | 'dispatchArgs'
  | 'wave'
  | 'bounce';

type BindingKind = 'uniform' | 'dynamic-uniform' | 'read-only-storage' | 'storage';

/** Where each binding lives; mirrors bind-scene.wgsl and bind-wavefront.wgsl. */
export const wavefrontBindingSlots: Record<WavefrontBindingName, { group: number; binding: number; kind: BindingKind }> = {
  frame: { group: 0, binding: 0, kind: 'uniform' },
  triangles: { group: 0, binding: 1, kind: 'read-only-storage' },
  triangleAttributes: { group: 0, binding: 2, kind: 'read-only-storage' },
  bvhNodes: { group: 0, binding: 3, kind: 'read-only-storage' },
  materials: { group: 0, binding: 4, kind: 'read-only-storage' },
  sceneObjects: { group: 0, binding: 5, kind: 'read-only-storage' },
  lights: { group: 0, binding: 6, kind: 'read-only-storage' },
  paths: { group: 1, binding: 0, kind: 'storage' },
  shadowRays: { group: 1, binding: 1, kind: 'storage' },
  counters: { group: 1, binding: 2, kind: 'storage' },
  tileRadiance: { group: 1, binding: 3, kind: 'storage' },
  accumulation: { group: 1, binding: 4, kind: 'storage' },
  dispatchArgs: { group: 1, binding: 5, kind: 'storage' },
  wave: { group: 2, binding: 0, kind: 'dynamic-uniform' },
  bounce: { group: 2, binding: 1, kind: 'dynamic-uniform' },
};

export interface WavefrontKernelSpec {
  module: string;
  entryPoint: string;
  bindings: readonly WavefrontBindingName[];
}

export const wavefrontKernels = {
  camera: { module: 'kernel-camera', entryPoint: 'generate_camera_rays', bindings: ['frame', 'paths', 'counters', 'tileRadiance', 'wave'] },
  prepareBounce: { module: 'kernel-prepare', entryPoint: 'prepare_bounce', bindings: ['counters', 'dispatchArgs', 'bounce'] },
  extend: { module: 'kernel-extend', entryPoint: 'extend_paths', bindings: ['frame', 'triangles', 'bvhNodes', 'sceneObjects', 'paths', 'counters', 'bounce'] },
  shade: {
    module: 'kernel-shade',
    entryPoint: 'shade_hits',
    bindings: ['frame', 'triangleAttributes', 'materials', 'sceneObjects', 'lights', 'paths', 'shadowRays', 'counters', 'tileRadiance', 'wave', 'bounce'],
  },
  prepareShadow: { module: 'kernel-prepare', entryPoint: 'prepare_shadow', bindings: ['counters', 'dispatchArgs'] },
  shadow: { module: 'kernel-shadow', entryPoint: 'trace_shadow_rays', bindings: ['frame', 'triangles', 'bvhNodes', 'sceneObjects', 'shadowRays', 'counters', 'tileRadiance'] },
  accumulate: { module: 'kernel-accumulate', entryPoint: 'accumulate_tile', bindings: ['frame', 'tileRadiance', 'accumulation', 'wave'] },
} as const satisfies Record<string, WavefrontKernelSpec>;

export type WavefrontKernelName = keyof typeof wavefrontKernels;

export function bindGroupLayoutEntries(spec: WavefrontKernelSpec, group: number): GPUBindGroupLayoutEntry[] {
  return spec.bindings
    .map((name) => wavefrontBindingSlots[name])
    .filter((slot) => slot.group === group)
    .sort((a, b) => a.binding - b.binding)
    .map((slot) => ({
      binding: slot.binding,
      visibility: ShaderStage.COMPUTE,
      buffer:
        slot.kind === 'uniform'
          ? { type: 'uniform' as const }
          : slot.kind === 'dynamic-uniform'
            ? { type: 'uniform' as const, hasDynamicOffset: true }
            : { type: slot.kind },
    }));
}

/** Groups a kernel uses, in order (a kernel with no group-0 binding still gets an empty group 0). */
export function kernelGroups(spec: WavefrontKernelSpec): number[] {
  const max = Math.max(...spec.bindings.map((b) => wavefrontBindingSlots[b].group));
  return Array.from({ length: max + 1 }, (_, g) => g);
}
