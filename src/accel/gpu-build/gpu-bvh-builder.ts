/**
 * GPU BVH construction (LBVH) and refit, in WGSL compute passes, writing exactly the records the
 * path tracer's traversal reads (records.ts BvhNode, parent links, primitives in BVH order), so a
 * tree built here traces with the same code as the CPU builder's.
 *
 * The build, one compute pass (the kernels cite their papers):
 *   1. centroid bounds, Morton keys with per-axis bit allocation (morton.wesl);
 *   2. stable LSD radix sort of (key, primitive) pairs, 4 bits per pass: count, device-wide scan,
 *      scatter (radix-sort.wesl, prefix-scan.wesl), 8 passes for 30-bit keys, 16 for 60-bit;
 *   3. Karras 2012 topology, one interior node per invocation, and the primitives gathered into
 *      sorted order (lbvh-hierarchy.wesl);
 *   4. bottom-up boxes with SAH leaf collapse (lbvh-fit.wesl);
 *   5. kept-node ranks by a scan, then the node records and parent links (lbvh-emit.wesl).
 * Nothing waits on another workgroup (WebGPU gives no forward-progress guarantee between them).
 *
 * The refit (refit.wesl) recomputes every box of a finished tree bottom-up after its primitives
 * moved, for poses that keep the topology.
 */
import { GpuRendererError } from '../../errors/gpu-renderer-error.ts';
import { BufferUsage, MapMode } from '../../gpu/webgpu-constants.ts';
import { bvhBuildConstants } from '../../gpu-layout/constants.ts';
import { bvhBuildUniformsLayout, bvhNodeLayout, primitiveLayout } from '../../gpu-layout/records.ts';
import { writeStruct } from '../../gpu-layout/struct-layout.ts';
import { dynamicUniformStride } from '../../gpu-layout/constants.ts';
import type { KernelPipeline } from '../../pathtracer/pipelines.ts';
import { bvhBuildBindings } from './bindings.ts';
import { bvhBuildPipelines, type BvhBuildKernel, type BvhBuildPipelines } from './pipelines.ts';

const C = bvhBuildConstants;

export interface GpuBvhBuildOptions {
  /** Morton key length: 30 bits (default; 8 sort passes) or 60 bits (16 passes; finer on scenes of very uneven density). */
  mortonBits?: 30 | 60;
  /**
   * Subtrees of at most this many primitives become one leaf where the SAH says a leaf is cheaper
   * (Karras and Aila 2013); default 8, 1 keeps one primitive per leaf.
   */
  maxLeafSize?: number;
  /** SAH cost of visiting an interior node relative to one primitive test (default 1, as bvh-sah.ts). */
  traversalCost?: number;
}

/** Where the build reads and writes: buffers of the caller (the renderer's scene buffers). */
export interface GpuBvhBuffers {
  /** Primitive records in scene order (input; needles already collapsed by packPrimitives). */
  source: GPUBuffer;
  primitiveCount: number;
  /** Output: the primitive records in BVH slot order (primitiveCount records). */
  primitives: GPUBuffer;
  /** Output: node records, room for 2 * primitiveCount - 1. */
  nodes: GPUBuffer;
  /** Output: parent links, room for 2 * primitiveCount - 1. */
  parents: GPUBuffer;
}

export interface GpuBvhBuildResult {
  nodeCount: number;
  /** Edges from the root to the deepest leaf. */
  depth: number;
  leafCount: number;
  /** SAH cost under the bvh-sah.ts model (C_trav = traversalCost, C_isect = 1), from the GPU's own sums. */
  sahCost: number;
  /** Wall time from submission until the GPU finished and the figures were read back, ms. */
  buildTimeMs: number;
  /** GPU time of the build's compute pass (timestamp queries), ms; null where the device has none. */
  gpuTimeMs: number | null;
}

export interface GpuBvhRefitResult {
  /** Wall time from submission until the GPU finished, ms. */
  refitTimeMs: number;
  gpuTimeMs: number | null;
}

/** Workgroups for `items` one-per-thread invocations, folded into rows of at most `maxX`. */
function grid(workgroups: number, maxX: number): [number, number] {
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
class UniformSlots {
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

type Resources = Partial<Record<keyof typeof bvhBuildBindings, GPUBuffer>>;

function bindGroup(device: GPUDevice, k: KernelPipeline, resources: Resources, label: string): GPUBindGroup {
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

interface Dispatch {
  kernel: BvhBuildKernel;
  group: GPUBindGroup;
  offset: number;
  workgroups: [number, number];
}

/** Timestamps around one compute pass, where the device has them. */
class PassTimer {
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
async function runPass(
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

function requireBufferSize(buffer: GPUBuffer, bytes: number, what: string): void {
  if (buffer.size < bytes) throw new RangeError(`GpuBvhBuilder: ${what} holds ${buffer.size} bytes, needs ${bytes}`);
}

/**
 * Builds (and rebuilds, and refits) the BVH of one primitive buffer on the GPU. Scratch buffers
 * (about 80 bytes per primitive) live until `releaseScratch` or `destroy`; the sort order (4 bytes
 * per primitive) stays for `refit`, which re-gathers the moved primitives into BVH order.
 */
export class GpuBvhBuilder {
  readonly device: GPUDevice;
  readonly primitiveCount: number;
  private readonly pipelines: BvhBuildPipelines;
  private readonly buffers: GpuBvhBuffers;
  private readonly keyWords: 1 | 2;
  private readonly base: Record<string, number>;
  private readonly timer: PassTimer | null;
  private readonly maxX: number;
  /** Sorted primitive index per slot: the first half of the sort's ping-pong values. */
  private readonly order: GPUBuffer;
  private readonly summary: GPUBuffer;
  private readonly summaryRead: GPUBuffer;
  private scratch: { buffers: GPUBuffer[]; uniforms: GPUBuffer; dispatches: Dispatch[]; clears: GPUBuffer[] } | null = null;
  private refitState: { nodeCount: number; uniforms: GPUBuffer; flags: GPUBuffer; dispatches: Dispatch[] } | null = null;
  private built: GpuBvhBuildResult | null = null;

  private constructor(device: GPUDevice, pipelines: BvhBuildPipelines, buffers: GpuBvhBuffers, options: GpuBvhBuildOptions) {
    this.device = device;
    this.pipelines = pipelines;
    this.buffers = buffers;
    const n = buffers.primitiveCount;
    this.primitiveCount = n;
    const mortonBits = options.mortonBits ?? 30;
    if (mortonBits !== 30 && mortonBits !== 60) throw new RangeError(`GpuBvhBuilder: mortonBits must be 30 or 60, got ${String(mortonBits)}`);
    this.keyWords = mortonBits === 60 ? 2 : 1;
    const maxLeafSize = options.maxLeafSize ?? 8;
    if (!Number.isInteger(maxLeafSize) || maxLeafSize < 1 || maxLeafSize > 64) throw new RangeError(`GpuBvhBuilder: maxLeafSize must be an integer in 1..64, got ${maxLeafSize}`);
    const traversalCost = options.traversalCost ?? 1;
    if (!(traversalCost > 0 && Number.isFinite(traversalCost))) throw new RangeError(`GpuBvhBuilder: traversalCost must be positive, got ${traversalCost}`);
    if (!Number.isInteger(n) || n < 1) throw new RangeError(`GpuBvhBuilder: primitiveCount must be a positive integer, got ${n}`);
    requireBufferSize(buffers.source, n * primitiveLayout.size, 'source');
    requireBufferSize(buffers.primitives, n * primitiveLayout.size, 'primitives');
    requireBufferSize(buffers.nodes, (2 * n - 1) * bvhNodeLayout.size, 'nodes');
    requireBufferSize(buffers.parents, (2 * n - 1) * 4, 'parents');
    this.base = { primitiveCount: n, internalCount: n - 1, keyWords: this.keyWords, maxLeafSize, traversalCost, intersectionCost: 1 };
    this.timer = device.features.has('timestamp-query') ? new PassTimer(device) : null;
    this.maxX = device.limits.maxComputeWorkgroupsPerDimension;
    this.order = this.storage('bvh sort values', n * 4);
    this.summary = this.storage('bvh build summary', C.BVH_SUMMARY_WORDS * 4, BufferUsage.COPY_SRC);
    this.summaryRead = device.createBuffer({ label: 'bvh build summary read', size: C.BVH_SUMMARY_WORDS * 4, usage: BufferUsage.MAP_READ | BufferUsage.COPY_DST });
  }

  /** A builder for `buffers`, with its pipelines compiled (once per device). */
  static async create(device: GPUDevice, buffers: GpuBvhBuffers, options: GpuBvhBuildOptions = {}): Promise<GpuBvhBuilder> {
    return new GpuBvhBuilder(device, await bvhBuildPipelines(device), buffers, options);
  }

  private storage(label: string, bytes: number, extra = 0): GPUBuffer {
    return this.device.createBuffer({ label, size: Math.max(16, Math.ceil(bytes / 4) * 4), usage: BufferUsage.STORAGE | BufferUsage.COPY_DST | extra });
  }

  private groups(items: number): [number, number] {
    return grid(Math.ceil(items / C.BVH_BUILD_WORKGROUP), this.maxX);
  }

  /** Scratch buffers, bind groups and the dispatch list of a build, made on first use. */
  private plan(): NonNullable<GpuBvhBuilder['scratch']> {
    if (this.scratch) return this.scratch;
    const device = this.device;
    const n = this.primitiveCount;
    const m = n - 1;
    const kw = this.keyWords;
    const p = this.pipelines;
    const created: GPUBuffer[] = [];
    const make = (label: string, bytes: number): GPUBuffer => {
      const b = this.storage(label, bytes);
      created.push(b);
      return b;
    };
    const state = make('bvh centroid bounds', 8 * 4);
    const keysA = make('bvh keys A', n * kw * 4);
    const keysB = make('bvh keys B', n * kw * 4);
    const valuesB = make('bvh values B', n * 4);
    const blocks = Math.ceil(n / C.BVH_SORT_BLOCK);
    const histogram = make('bvh sort histogram', C.BVH_SORT_RADIX * blocks * 4);
    const histogramLevels = scanLevels(C.BVH_SORT_RADIX * blocks);
    const rankLevels = scanLevels(Math.max(1, m));
    // sums[l]: the block totals of level l (scanned in place as level l + 1).
    const sums: GPUBuffer[] = [];
    for (let l = 0; l < Math.max(histogramLevels.length, rankLevels.length); l++) {
      const blocksOf = (levels: number[]): number => Math.ceil((levels[l] ?? 0) / C.BVH_SCAN_BLOCK);
      sums.push(make(`bvh scan sums ${l}`, Math.max(blocksOf(histogramLevels), blocksOf(rankLevels)) * 4));
    }
    const lbvhNodes = make('lbvh nodes', Math.max(1, m) * 16);
    const lbvhParents = make('lbvh parents', (n + m) * 4);
    const lbvhData = make('lbvh data', Math.max(1, m) * C.BVH_DATA_WORDS * 4);
    const lbvhFlags = make('lbvh flags', Math.max(1, m) * 4);
    const lbvhRank = make('lbvh rank', Math.max(1, m) * 4);

    const slots = new UniformSlots();
    const base = slots.add(this.base);
    const dispatches: Dispatch[] = [];
    const { source, primitives, nodes, parents } = this.buffers;
    const order = this.order;
    const pending: { kernel: BvhBuildKernel; resources: Resources; offset: number; workgroups: [number, number]; label: string }[] = [];
    const lbvh: Resources = { lbvhNodes, lbvhParents, lbvhData };
    // Every program binds all the buffers it declares; dispatches override the ones that vary.
    const defaults: Resources = {
      buildPrimitives: source, buildState: state, sortKeysIn: keysA, sortValuesIn: order, sortKeysOut: keysA, sortValuesOut: order,
      gatheredPrimitives: primitives, sortedPrimitives: primitives, ...lbvh, lbvhFlags, lbvhRank, outNodes: nodes, outParents: parents,
      buildSummary: this.summary,
    };
    const add = (kernel: BvhBuildKernel, resources: Resources, offset: number, workgroups: [number, number], label: string): void => {
      pending.push({ kernel, resources: { ...defaults, ...resources }, offset, workgroups, label });
    };
    const scan = (data: GPUBuffer, levels: number[], label: string): void => {
      const offsets = levels.map((length) => slots.add({ ...this.base, scanLength: length }));
      const levelData = (l: number): GPUBuffer => (l === 0 ? data : sums[l - 1]!);
      for (let l = 0; l < levels.length; l++) {
        add('scanBlocks', { scanData: levelData(l), scanSums: sums[l]! }, offsets[l]!, grid(Math.ceil(levels[l]! / C.BVH_SCAN_BLOCK), this.maxX), `${label} scan ${l}`);
      }
      for (let l = levels.length - 2; l >= 0; l--) {
        add('scanAdd', { scanData: levelData(l), scanSums: sums[l]! }, offsets[l]!, grid(Math.ceil(levels[l]! / C.BVH_SCAN_BLOCK), this.maxX), `${label} add ${l}`);
      }
    };

    add('centroidBounds', { buildPrimitives: source, buildState: state }, base, this.groups(n), 'centroid bounds');
    add('mortonCodes', { buildPrimitives: source, buildState: state, sortKeysOut: keysA, sortValuesOut: order }, base, this.groups(n), 'morton codes');
    const passes = 8 * kw;
    for (let pass = 0; pass < passes; pass++) {
      const even = pass % 2 === 0;
      const io: Resources = {
        sortKeysIn: even ? keysA : keysB, sortValuesIn: even ? order : valuesB,
        sortKeysOut: even ? keysB : keysA, sortValuesOut: even ? valuesB : order,
        sortHistogram: histogram,
      };
      const offset = slots.add({ ...this.base, digitShift: 4 * (pass % 8), digitWord: Math.floor(pass / 8), blockCount: blocks });
      add('sortCount', io, offset, grid(blocks, this.maxX), `sort count ${pass}`);
      scan(histogram, histogramLevels, `sort ${pass}`);
      add('sortScatter', io, offset, grid(blocks, this.maxX), `sort scatter ${pass}`);
    }
    // An even number of passes leaves the sorted pairs in keysA and `order`.
    if (m > 0) add('hierarchy', { sortKeysIn: keysA, ...lbvh }, base, this.groups(m), 'lbvh hierarchy');
    add('gather', { sortValuesIn: order, buildPrimitives: source, gatheredPrimitives: primitives }, base, this.groups(n), 'gather primitives');
    const emit: Resources = { sortedPrimitives: primitives, ...lbvh, lbvhRank, outNodes: nodes, outParents: parents, buildSummary: this.summary };
    if (m > 0) {
      add('fit', { sortedPrimitives: primitives, ...lbvh, lbvhFlags, buildSummary: this.summary }, base, this.groups(n), 'lbvh fit');
      add('markKept', emit, base, this.groups(m), 'mark kept');
      scan(lbvhRank, rankLevels, 'kept');
      add('emitNodes', emit, base, this.groups(m), 'emit nodes');
    }
    add('writeSummary', emit, base, [1, 1], 'write summary');

    const uniforms = slots.upload(device, null);
    created.push(uniforms);
    for (const d of pending) {
      dispatches.push({ kernel: d.kernel, group: bindGroup(device, p[d.kernel], { ...d.resources, bvhBuild: uniforms }, d.label), offset: d.offset, workgroups: d.workgroups });
    }
    this.scratch = { buffers: created, uniforms, dispatches, clears: [state, lbvhFlags] };
    return this.scratch;
  }

  private async readSummary(): Promise<Uint32Array> {
    await this.summaryRead.mapAsync(MapMode.READ);
    const words = new Uint32Array(this.summaryRead.getMappedRange().slice(0));
    this.summaryRead.unmap();
    if (words[C.BVH_SUMMARY_ERRORS] !== 0) {
      throw new GpuRendererError('ACCELERATION_BUILD_FAILED', 'a bottom-up BVH pass never saw a child box published by another workgroup (the device did not make the stores visible)');
    }
    return words;
  }

  /** Builds the tree from the current contents of `source` into the output buffers. */
  async build(): Promise<GpuBvhBuildResult> {
    const plan = this.plan();
    const { wallMs, gpuMs } = await runPass(
      this.device,
      this.pipelines,
      plan.dispatches,
      (encoder) => {
        for (const b of plan.clears) encoder.clearBuffer(b);
        encoder.clearBuffer(this.summary);
      },
      (encoder) => encoder.copyBufferToBuffer(this.summary, 0, this.summaryRead, 0, C.BVH_SUMMARY_WORDS * 4),
      this.timer,
      'gpu bvh build',
    );
    const t0 = performance.now();
    const words = await this.readSummary();
    const readMs = performance.now() - t0;
    const sah = new Float32Array(words.buffer)[C.BVH_SUMMARY_SAH_COST]!;
    this.built = {
      nodeCount: words[C.BVH_SUMMARY_NODE_COUNT]!,
      depth: words[C.BVH_SUMMARY_DEPTH]!,
      leafCount: words[C.BVH_SUMMARY_LEAF_COUNT]!,
      sahCost: sah,
      buildTimeMs: wallMs + readMs,
      gpuTimeMs: gpuMs,
    };
    return this.built;
  }

  /** Frees the build's scratch (about 80 bytes per primitive); a later build makes it again. */
  releaseScratch(): void {
    if (!this.scratch) return;
    for (const b of this.scratch.buffers) b.destroy();
    this.scratch = null;
  }

  /**
   * After the caller rewrote `source` with moved primitives (same count, same meaning of each
   * record): gathers them into the built tree's order and refits every box. The tree keeps its
   * topology, so its SAH cost drifts with the pose; rebuild when it matters.
   */
  async refit(): Promise<GpuBvhRefitResult> {
    if (!this.built) throw new GpuRendererError('INVALID_STATE', 'refit needs a built tree: call build() first');
    const state = this.refitPlan(this.built.nodeCount);
    const { wallMs, gpuMs } = await runPass(
      this.device,
      this.pipelines,
      state.dispatches,
      (encoder) => encoder.clearBuffer(this.summary),
      (encoder) => encoder.copyBufferToBuffer(this.summary, 0, this.summaryRead, 0, C.BVH_SUMMARY_WORDS * 4),
      this.timer,
      'gpu bvh refit',
    );
    await this.readSummary();
    return { refitTimeMs: wallMs, gpuTimeMs: gpuMs };
  }

  private refitPlan(nodeCount: number): NonNullable<GpuBvhBuilder['refitState']> {
    if (this.refitState && this.refitState.nodeCount === nodeCount) return this.refitState;
    this.refitState?.uniforms.destroy();
    this.refitState?.flags.destroy();
    const { source, primitives } = this.buffers;
    const slots = new UniformSlots();
    const offset = slots.add({ ...this.base, nodeCount });
    const uniforms = slots.upload(this.device, null);
    const flags = this.storage('bvh refit flags', nodeCount * 4);
    const gather = bindGroup(this.device, this.pipelines.gather, { bvhBuild: uniforms, sortValuesIn: this.order, buildPrimitives: source, gatheredPrimitives: primitives }, 'refit gather');
    const refit = refitDispatches(this.device, this.pipelines, { nodes: this.buffers.nodes, parents: this.buffers.parents, primitives, nodeCount }, uniforms, offset, flags, this.summary);
    this.refitState = { nodeCount, uniforms, flags, dispatches: [{ kernel: 'gather', group: gather, offset, workgroups: this.groups(this.primitiveCount) }, ...refit] };
    return this.refitState;
  }

  destroy(): void {
    this.releaseScratch();
    this.refitState?.uniforms.destroy();
    this.refitState?.flags.destroy();
    this.refitState = null;
    this.order.destroy();
    this.summary.destroy();
    this.summaryRead.destroy();
    this.timer?.destroy();
  }
}

/** The tree a refit updates: buffers in the traversal's format, with `nodeCount` records. */
export interface RefitTarget {
  nodes: GPUBuffer;
  parents: GPUBuffer;
  /** Primitive records in BVH slot order, already holding the moved geometry. */
  primitives: GPUBuffer;
  nodeCount: number;
}

function refitDispatches(device: GPUDevice, p: BvhBuildPipelines, t: RefitTarget, uniforms: GPUBuffer, offset: number, flags: GPUBuffer, summary: GPUBuffer): Dispatch[] {
  const resources: Resources = { bvhBuild: uniforms, refitNodes: t.nodes, refitParents: t.parents, refitFlags: flags, sortedPrimitives: t.primitives, buildSummary: summary };
  const workgroups = grid(Math.ceil(t.nodeCount / C.BVH_BUILD_WORKGROUP), device.limits.maxComputeWorkgroupsPerDimension);
  return [
    { kernel: 'refitReset', group: bindGroup(device, p.refitReset, resources, 'refit reset'), offset, workgroups },
    { kernel: 'refitNodes', group: bindGroup(device, p.refitNodes, resources, 'refit nodes'), offset, workgroups },
  ];
}

/**
 * Refits a tree built elsewhere (the CPU builder's, uploaded) after its primitives moved: the boxes
 * of `target.nodes` are recomputed on the GPU from `target.primitives`. Holds a flag per node.
 */
export class GpuBvhRefitter {
  private readonly device: GPUDevice;
  private readonly pipelines: BvhBuildPipelines;
  private readonly uniforms: GPUBuffer;
  private readonly flags: GPUBuffer;
  private readonly summary: GPUBuffer;
  private readonly summaryRead: GPUBuffer;
  private readonly dispatches: Dispatch[];

  private constructor(device: GPUDevice, pipelines: BvhBuildPipelines, target: RefitTarget) {
    this.device = device;
    this.pipelines = pipelines;
    if (!Number.isInteger(target.nodeCount) || target.nodeCount < 1) throw new RangeError(`GpuBvhRefitter: nodeCount must be a positive integer, got ${target.nodeCount}`);
    requireBufferSize(target.nodes, target.nodeCount * bvhNodeLayout.size, 'nodes');
    requireBufferSize(target.parents, target.nodeCount * 4, 'parents');
    const slots = new UniformSlots();
    const offset = slots.add({ nodeCount: target.nodeCount, traversalCost: 1, intersectionCost: 1 });
    this.uniforms = slots.upload(device, null);
    const storage = (label: string, bytes: number, extra = 0): GPUBuffer =>
      device.createBuffer({ label, size: Math.max(16, bytes), usage: BufferUsage.STORAGE | BufferUsage.COPY_DST | extra });
    this.flags = storage('bvh refit flags', target.nodeCount * 4);
    this.summary = storage('bvh refit summary', C.BVH_SUMMARY_WORDS * 4, BufferUsage.COPY_SRC);
    this.summaryRead = device.createBuffer({ size: C.BVH_SUMMARY_WORDS * 4, usage: BufferUsage.MAP_READ | BufferUsage.COPY_DST });
    this.dispatches = refitDispatches(device, pipelines, target, this.uniforms, offset, this.flags, this.summary);
  }

  static async create(device: GPUDevice, target: RefitTarget): Promise<GpuBvhRefitter> {
    return new GpuBvhRefitter(device, await bvhBuildPipelines(device), target);
  }

  async refit(): Promise<GpuBvhRefitResult> {
    const { wallMs } = await runPass(
      this.device,
      this.pipelines,
      this.dispatches,
      (encoder) => encoder.clearBuffer(this.summary),
      (encoder) => encoder.copyBufferToBuffer(this.summary, 0, this.summaryRead, 0, C.BVH_SUMMARY_WORDS * 4),
      null,
      'gpu bvh refit',
    );
    await this.summaryRead.mapAsync(MapMode.READ);
    const errors = new Uint32Array(this.summaryRead.getMappedRange().slice(0))[C.BVH_SUMMARY_ERRORS];
    this.summaryRead.unmap();
    if (errors !== 0) throw new GpuRendererError('ACCELERATION_BUILD_FAILED', 'a bottom-up refit pass never saw a child box published by another workgroup');
    return { refitTimeMs: wallMs, gpuTimeMs: null };
  }

  destroy(): void {
    this.uniforms.destroy();
    this.flags.destroy();
    this.summary.destroy();
    this.summaryRead.destroy();
  }
}
