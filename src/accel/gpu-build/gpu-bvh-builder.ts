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
import { bvhNodeLayout, primitiveLayout } from '../../gpu-layout/records.ts';
import { DispatchList, PassTimer, runPass, scanSumsWords, type Dispatch } from './dispatch-plan.ts';
import { bvhBuildPipelines, type BvhBuildPipelines } from './pipelines.ts';
import { radixSortScratchWords, recordRadixSort, type RadixSortBuffers } from './radix-sort.ts';

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
  /** Sorted primitive index per slot: the first half of the sort's ping-pong values. */
  private readonly order: GPUBuffer;
  private readonly summary: GPUBuffer;
  private readonly summaryRead: GPUBuffer;
  private scratch: { buffers: GPUBuffer[]; dispatches: Dispatch[]; clears: GPUBuffer[] } | null = null;
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

  /** Scratch buffers, bind groups and the dispatch list of a build, made on first use. */
  private plan(): NonNullable<GpuBvhBuilder['scratch']> {
    if (this.scratch) return this.scratch;
    const n = this.primitiveCount;
    const m = n - 1;
    const kw = this.keyWords;
    const created: GPUBuffer[] = [];
    const make = (label: string, bytes: number): GPUBuffer => {
      const b = this.storage(label, bytes);
      created.push(b);
      return b;
    };
    const sortScratch = radixSortScratchWords(n);
    const sums = scanSumsWords([sortScratch.histogram, Math.max(1, m)]).map((words, l) => make(`bvh scan sums ${l}`, words * 4));
    const sort: RadixSortBuffers = {
      keys: make('bvh keys', n * kw * 4),
      keysScratch: make('bvh keys scratch', n * kw * 4),
      values: this.order,
      valuesScratch: make('bvh values scratch', n * 4),
      histogram: make('bvh sort histogram', sortScratch.histogram * 4),
      sums,
    };
    const state = make('bvh centroid bounds and Morton bit schedule', 16 * 4);
    const lbvhNodes = make('lbvh nodes', Math.max(1, m) * 16);
    const lbvhParents = make('lbvh parents', (n + m) * 4);
    const lbvhData = make('lbvh data', Math.max(1, m) * C.BVH_DATA_WORDS * 4);
    const lbvhFlags = make('lbvh flags', Math.max(1, m) * 4);
    const lbvhRank = make('lbvh rank', Math.max(1, m) * 4);
    const { source, primitives, nodes, parents } = this.buffers;
    // Every program binds all the buffers it declares; dispatches override the ones that vary.
    const list = new DispatchList(this.device, this.pipelines, {
      buildPrimitives: source, buildState: state, sortKeysIn: sort.keys, sortValuesIn: this.order, sortKeysOut: sort.keys, sortValuesOut: this.order,
      gatheredPrimitives: primitives, sortedPrimitives: primitives, lbvhNodes, lbvhParents, lbvhData, lbvhRecords: lbvhData, lbvhFlags, lbvhRank,
      outNodes: nodes, outParents: parents, buildSummary: this.summary,
    });
    const base = list.slot(this.base);
    list.add('centroidBounds', {}, base, list.blocks(Math.ceil(n / (C.BVH_REDUCE_ITEMS * C.BVH_BUILD_WORKGROUP))), 'centroid bounds');
    list.add('mortonSchedule', {}, base, [1, 1], 'morton bit schedule');
    list.add('mortonCodes', {}, base, list.items(n), 'morton codes');
    recordRadixSort(list, sort, n, kw, this.base);
    if (m > 0) list.add('hierarchy', {}, base, list.items(m), 'lbvh hierarchy');
    list.add('gather', {}, base, list.items(n), 'gather primitives');
    if (m > 0) {
      list.add('fit', {}, base, list.items(n), 'lbvh fit');
      list.add('markKept', {}, base, list.items(m), 'mark kept');
      list.scan(lbvhRank, m, sums, this.base, 'kept');
      list.add('emitNodes', {}, base, list.items(m), 'emit nodes');
    }
    list.add('writeSummary', {}, base, [1, 1], 'write summary');
    const { uniforms, dispatches } = list.finish();
    created.push(uniforms);
    this.scratch = { buffers: created, dispatches, clears: [state, lbvhFlags] };
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
    const { source, primitives, nodes, parents } = this.buffers;
    const flags = this.storage('bvh refit flags', nodeCount * 4);
    const list = new DispatchList(this.device, this.pipelines, {
      sortValuesIn: this.order, buildPrimitives: source, gatheredPrimitives: primitives,
      sortedPrimitives: primitives, refitNodes: nodes, refitParents: parents, refitFlags: flags, buildSummary: this.summary,
    });
    const offset = list.slot({ ...this.base, nodeCount });
    list.add('gather', {}, offset, list.items(this.primitiveCount), 'refit gather');
    recordRefit(list, nodeCount, offset);
    const { uniforms, dispatches } = list.finish();
    this.refitState = { nodeCount, uniforms, flags, dispatches };
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

function recordRefit(list: DispatchList, nodeCount: number, offset: number): void {
  list.add('refitReset', {}, offset, list.items(nodeCount), 'refit reset');
  list.add('refitNodes', {}, offset, list.items(nodeCount), 'refit nodes');
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
    const storage = (label: string, bytes: number, extra = 0): GPUBuffer =>
      device.createBuffer({ label, size: Math.max(16, bytes), usage: BufferUsage.STORAGE | BufferUsage.COPY_DST | extra });
    this.flags = storage('bvh refit flags', target.nodeCount * 4);
    this.summary = storage('bvh refit summary', C.BVH_SUMMARY_WORDS * 4, BufferUsage.COPY_SRC);
    this.summaryRead = device.createBuffer({ size: C.BVH_SUMMARY_WORDS * 4, usage: BufferUsage.MAP_READ | BufferUsage.COPY_DST });
    const list = new DispatchList(device, pipelines, {
      sortedPrimitives: target.primitives, refitNodes: target.nodes, refitParents: target.parents, refitFlags: this.flags, buildSummary: this.summary,
    });
    recordRefit(list, target.nodeCount, list.slot({ nodeCount: target.nodeCount }));
    const { uniforms, dispatches } = list.finish();
    this.uniforms = uniforms;
    this.dispatches = dispatches;
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
