/**
 * Plumbing shared by the GPU BVH passes: a list of dispatches recorded with the uniform slot and
 * buffers each reads, encoded later into one compute pass; the device-wide scan's levels.
 */
import { GpuRendererError } from '../../errors/gpu-renderer-error.ts';
import { BufferUsage, MapMode } from '../../gpu/webgpu-constants.ts';
import { bvhBuildConstants, dynamicUniformStride } from '../../gpu-layout/constants.ts';
import { bvhBuildUniformsLayout } from '../../gpu-layout/records.ts';
import { writeStruct } from '../../gpu-layout/struct-layout.ts';
import type { KernelPipeline } from '../../shaders/program-pipelines.ts';
import { bvhBuildBindings } from './bindings.ts';
import type { BvhBuildKernel, BvhBuildPipelines } from './pipelines.ts';

const C = bvhBuildConstants;

/** Workgroups for `items` one-per-thread invocations, folded into rows of at most `maxX`. */
export function grid(workgroups: number, maxX: number): [number, number] {
  if (workgroups <= maxX) return [Math.max(1, workgroups), 1];
  return [maxX, Math.ceil(workgroups / maxX)];
}

/** Element counts of the levels of a device-wide scan over `length` elements (level 0 first). */
export function scanLevels(length: number): number[] {
  const levels = [length];
  while (levels[levels.length - 1]! > C.BVH_SCAN_BLOCK) levels.push(Math.ceil(levels[levels.length - 1]! / C.BVH_SCAN_BLOCK));
  return levels;
}

/** Uniform slots (dynamic offsets) of one build: every dispatch names the slot it reads. */
export class UniformSlots {
  private readonly records: Record<string, number | number[]>[] = [];

  add(values: Record<string, number | number[]>): number {
    this.records.push(values);
    return (this.records.length - 1) * dynamicUniformStride;
  }

  upload(device: GPUDevice, buffer: GPUBuffer | null): GPUBuffer {
    const data = new ArrayBuffer(Math.max(1, this.records.length) * dynamicUniformStride);
    this.records.forEach((r, i) => writeStruct(bvhBuildUniformsLayout, new DataView(data, i * dynamicUniformStride, bvhBuildUniformsLayout.size), 0, r));
    const target = buffer ?? device.createBuffer({ label: 'bvh build uniforms', size: data.byteLength, usage: BufferUsage.UNIFORM | BufferUsage.COPY_DST });
    device.queue.writeBuffer(target, 0, data);
    return target;
  }
}

export type Resources = Partial<Record<keyof typeof bvhBuildBindings, GPUBuffer>>;

export function bindGroup(device: GPUDevice, k: KernelPipeline, resources: Resources, label: string): GPUBindGroup {
  const names = k.bindingsByGroup[0] ?? [];
  return device.createBindGroup({
    label,
    layout: k.groups[0]!,
    entries: names.map((name) => {
      const buffer = resources[name as keyof typeof bvhBuildBindings];
      if (!buffer) throw new Error(`bvh build: no buffer for binding ${name} (${label})`);
      const binding = bvhBuildBindings[name as keyof typeof bvhBuildBindings].binding;
      return name === 'bvhBuild' ? { binding, resource: { buffer, size: bvhBuildUniformsLayout.size } } : { binding, resource: { buffer } };
    }),
  });
}

export interface Dispatch {
  kernel: BvhBuildKernel;
  group: GPUBindGroup;
  offset: number;
  workgroups: [number, number];
}

/** Timestamps around one compute pass, where the device has them. */
export class PassTimer {
  readonly querySet: GPUQuerySet;
  private readonly resolve: GPUBuffer;
  private readonly read: GPUBuffer;

  constructor(device: GPUDevice) {
    this.querySet = device.createQuerySet({ type: 'timestamp', count: 2 });
    this.resolve = device.createBuffer({ size: 16, usage: BufferUsage.QUERY_RESOLVE | BufferUsage.COPY_SRC });
    this.read = device.createBuffer({ size: 16, usage: BufferUsage.MAP_READ | BufferUsage.COPY_DST });
  }

  writes(): GPUComputePassTimestampWrites {
    return { querySet: this.querySet, beginningOfPassWriteIndex: 0, endOfPassWriteIndex: 1 };
  }

  encodeResolve(encoder: GPUCommandEncoder): void {
    encoder.resolveQuerySet(this.querySet, 0, 2, this.resolve, 0);
    encoder.copyBufferToBuffer(this.resolve, 0, this.read, 0, 16);
  }

  async ms(): Promise<number> {
    await this.read.mapAsync(MapMode.READ);
    const t = new BigUint64Array(this.read.getMappedRange().slice(0));
    this.read.unmap();
    return Number(t[1]! - t[0]!) / 1e6;
  }

  destroy(): void {
    this.querySet.destroy();
    this.resolve.destroy();
    this.read.destroy();
  }
}

/** Encodes the dispatches into one compute pass and submits it after `before` (clears, copies). */
export async function runPass(
  device: GPUDevice,
  pipelines: BvhBuildPipelines,
  dispatches: readonly Dispatch[],
  before: (encoder: GPUCommandEncoder) => void,
  after: (encoder: GPUCommandEncoder) => void,
  timer: PassTimer | null,
  label: string,
): Promise<{ wallMs: number; gpuMs: number | null }> {
  device.pushErrorScope('validation');
  const encoder = device.createCommandEncoder({ label });
  before(encoder);
  const pass = encoder.beginComputePass({ label, ...(timer ? { timestampWrites: timer.writes() } : {}) });
  for (const d of dispatches) {
    pass.setPipeline(pipelines[d.kernel].pipeline);
    pass.setBindGroup(0, d.group, [d.offset]);
    pass.dispatchWorkgroups(d.workgroups[0], d.workgroups[1]);
  }
  pass.end();
  timer?.encodeResolve(encoder);
  after(encoder);
  const started = performance.now();
  device.queue.submit([encoder.finish()]);
  const validation = await device.popErrorScope();
  if (validation) throw new GpuRendererError('GPU_VALIDATION_FAILED', `${label}: ${validation.message}`);
  await device.queue.onSubmittedWorkDone();
  const wallMs = performance.now() - started;
  return { wallMs, gpuMs: timer ? await timer.ms() : null };
}

/**
 * Dispatches recorded in order, each with its uniform slot (a dynamic offset into one uniform
 * buffer) and the buffers of its program (`defaults`, overridden per dispatch).
 */
export class DispatchList {
  private readonly device: GPUDevice;
  private readonly pipelines: BvhBuildPipelines;
  private readonly defaults: Resources;
  private readonly slots = new UniformSlots();
  private readonly pending: { kernel: BvhBuildKernel; resources: Resources; offset: number; workgroups: [number, number]; label: string }[] = [];

  constructor(device: GPUDevice, pipelines: BvhBuildPipelines, defaults: Resources) {
    this.device = device;
    this.pipelines = pipelines;
    this.defaults = defaults;
  }

  /** A uniform slot holding `values`; returns its dynamic offset. */
  slot(values: Record<string, number | number[]>): number {
    return this.slots.add(values);
  }

  /** Workgroups for `items` one-per-invocation items. */
  items(items: number): [number, number] {
    return grid(Math.ceil(items / C.BVH_BUILD_WORKGROUP), this.device.limits.maxComputeWorkgroupsPerDimension);
  }

  /** Workgroups for `blocks` one-per-workgroup blocks. */
  blocks(blocks: number): [number, number] {
    return grid(blocks, this.device.limits.maxComputeWorkgroupsPerDimension);
  }

  add(kernel: BvhBuildKernel, resources: Resources, offset: number, workgroups: [number, number], label: string): void {
    this.pending.push({ kernel, resources: { ...this.defaults, ...resources }, offset, workgroups, label });
  }

  /**
   * Exclusive prefix sum of `data` (scanLevels(length) levels): each level's blocks are scanned and
   * their totals written to sums[level], which the next level scans; then totals are added back
   * from the top. `sums[l]` needs room for ceil(levels[l] / BVH_SCAN_BLOCK) words.
   */
  scan(data: GPUBuffer, length: number, sums: readonly GPUBuffer[], base: Record<string, number>, label: string): void {
    const levels = scanLevels(length);
    const offsets = levels.map((scanLength) => this.slot({ ...base, scanLength }));
    const levelData = (l: number): GPUBuffer => (l === 0 ? data : sums[l - 1]!);
    const groups = (l: number): [number, number] => this.blocks(Math.ceil(levels[l]! / C.BVH_SCAN_BLOCK));
    for (let l = 0; l < levels.length; l++) this.add('scanBlocks', { scanData: levelData(l), scanSums: sums[l]! }, offsets[l]!, groups(l), `${label} scan ${l}`);
    for (let l = levels.length - 2; l >= 0; l--) this.add('scanAdd', { scanData: levelData(l), scanSums: sums[l]! }, offsets[l]!, groups(l), `${label} add ${l}`);
  }

  /** Uploads the uniform slots and makes the bind groups. */
  finish(): { uniforms: GPUBuffer; dispatches: Dispatch[] } {
    const uniforms = this.slots.upload(this.device, null);
    const dispatches = this.pending.map((d) => ({
      kernel: d.kernel,
      group: bindGroup(this.device, this.pipelines[d.kernel], { ...d.resources, bvhBuild: uniforms }, d.label),
      offset: d.offset,
      workgroups: d.workgroups,
    }));
    return { uniforms, dispatches };
  }
}

/** Words of scan sums needed at each level for scans of up to these lengths. */
export function scanSumsWords(lengths: readonly number[]): number[] {
  const per = lengths.map(scanLevels);
  const depth = Math.max(...per.map((l) => l.length));
  return Array.from({ length: depth }, (_, l) => Math.max(1, ...per.map((levels) => Math.ceil((levels[l] ?? 0) / C.BVH_SCAN_BLOCK))));
}
