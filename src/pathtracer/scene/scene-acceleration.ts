/**
 * The renderer's BVH on the device, in either build mode, and how it follows moved geometry:
 *
 * - 'cpu-upload' (default): the CPU binned-SAH tree prepareScene built is uploaded with the
 *   primitives; a refit recomputes its boxes on the GPU (GpuBvhRefitter), a rebuild runs the CPU
 *   builder again and uploads.
 * - 'gpu': prepareScene leaves the records in scene order; they go to a source buffer and the GPU
 *   LBVH builder writes primitives, nodes and parent links; a refit re-gathers and refits on the
 *   GPU, a rebuild runs the GPU build again.
 *
 * Either way the traversal reads the same three buffers in the same format. Bottom-level trees of
 * shared meshes (instancing.ts) follow the top level in the same buffers; only the top level
 * follows moved placements.
 */
import { buildBvhAsync } from '../../accel/bvh-builder.ts';
import { GpuBvhBuilder, GpuBvhRefitter } from '../../accel/gpu-build/gpu-bvh-builder.ts';
import { bvhParentLinks, packPrimitives, packWavefrontBvhNodes } from '../../accel/triangle-packing.ts';
import { BufferUsage } from '../../gpu/webgpu-constants.ts';
import { bvhNodeLayout, primitiveLayout } from '../../gpu-layout/records.ts';
import type { GpuBufferSet } from '../gpu-buffers.ts';
import type { AccelerationBuildMode, PreparedScene } from './prepare-scene.ts';
import { applyTopLevelPatch, type TopLevelUpdate } from './top-level-patch.ts';

export type BvhUpdateMode = 'refit' | 'rebuild';

export interface SceneBvhBuffers {
  primitives: GPUBuffer;
  bvhNodes: GPUBuffer;
  bvhParents: GPUBuffer;
}

function identity(count: number): Uint32Array {
  return Uint32Array.from({ length: count }, (_, i) => i);
}

export class SceneAcceleration {
  readonly mode: AccelerationBuildMode;
  private readonly device: GPUDevice;
  private readonly prepared: PreparedScene;
  private readonly buffers: SceneBvhBuffers;
  private readonly builder: GpuBvhBuilder | null;
  private readonly source: GPUBuffer | null;
  private readonly owner: GpuBufferSet | null;
  private refitter: GpuBvhRefitter | null = null;

  private constructor(device: GPUDevice, prepared: PreparedScene, buffers: SceneBvhBuffers, gpu: { builder: GpuBvhBuilder; source: GPUBuffer; owner: GpuBufferSet } | null) {
    this.device = device;
    this.prepared = prepared;
    this.buffers = buffers;
    this.mode = prepared.acceleration.mode;
    this.builder = gpu?.builder ?? null;
    this.source = gpu?.source ?? null;
    this.owner = gpu?.owner ?? null;
  }

  /**
   * Takes over the uploaded scene buffers; in 'gpu' mode uploads the scene-order records and builds
   * the tree on the GPU (filling in `prepared.bvh`). `owner` tracks the source buffer's memory.
   */
  static async create(device: GPUDevice, prepared: PreparedScene, buffers: SceneBvhBuffers, owner: GpuBufferSet): Promise<SceneAcceleration> {
    if (prepared.acceleration.mode !== 'gpu') {
      const acceleration = new SceneAcceleration(device, prepared, buffers, null);
      acceleration.writeBottomLevels();
      return acceleration;
    }
    const source = owner.upload('bvhSource', prepared.primitives, BufferUsage.STORAGE, 'scene');
    const builder = await GpuBvhBuilder.create(device, { source, primitiveCount: prepared.primitiveCount, primitives: buffers.primitives, nodes: buffers.bvhNodes, parents: buffers.bvhParents });
    const acceleration = new SceneAcceleration(device, prepared, buffers, { builder, source, owner });
    await acceleration.buildOnGpu();
    acceleration.writeBottomLevels();
    return acceleration;
  }

  /**
   * The bottom levels (CPU-built, instancing.ts) after the room of any top-level tree: only the
   * top level is ever built on the GPU or rebuilt, so they are written once and again on a refit.
   */
  private writeBottomLevels(): void {
    const b = this.prepared.bottomLevels;
    if (!b) return;
    const queue = this.device.queue;
    this.writePlacementTransforms(this.prepared.placementTransforms.records);
    queue.writeBuffer(this.buffers.primitives, b.primitiveBase * primitiveLayout.size, b.primitives);
    queue.writeBuffer(this.buffers.bvhNodes, b.nodeBase * bvhNodeLayout.size, b.nodes);
    queue.writeBuffer(this.buffers.bvhParents, b.nodeBase * 4, b.parents.buffer, b.parents.byteOffset, b.parents.byteLength);
  }

  private async buildOnGpu(): Promise<void> {
    const result = await this.builder!.build();
    // The scratch (sort keys, LBVH nodes) is made again by the next rebuild; the order stays for refits.
    this.builder!.releaseScratch();
    this.prepared.bvh = { nodeCount: result.nodeCount, depth: result.depth, sahCost: result.sahCost, buildTimeMs: result.buildTimeMs };
  }

  private writePlacementTransforms(records: ArrayBuffer): void {
    if (records.byteLength === 0) return;
    this.device.queue.writeBuffer(this.buffers.primitives, this.prepared.placementTransforms.base * primitiveLayout.size, records);
  }

  /**
   * The scene's primitives moved (same primitives, same count): brings the tree along. A refit
   * keeps the topology and recomputes every box on the GPU; a rebuild builds a fresh tree in this
   * scene's mode. A patch (only instances moved) rewrites just their records. Returns the wall
   * time of the BVH work, ms.
   */
  async update(topLevel: TopLevelUpdate, how: BvhUpdateMode, bottomLevelsMoved = false): Promise<number> {
    const started = performance.now();
    const queue = this.device.queue;
    if (bottomLevelsMoved) this.writeBottomLevels();
    // The records as uploaded: to the GPU builder's scene-order source in 'gpu' mode, else in tree order.
    const target = this.mode === 'gpu' ? this.source! : this.buffers.primitives;
    if (topLevel.patch) {
      if (how !== 'refit') throw new RangeError('SceneAcceleration.update: a patch of moved instances is refitted, not rebuilt');
      const { first, end } = applyTopLevelPatch(this.prepared, topLevel.patch);
      const size = primitiveLayout.size;
      if (end > first) queue.writeBuffer(target, first * size, this.prepared.primitives, first * size, (end - first) * size);
      this.writePlacementTransforms(this.prepared.placementTransforms.records);
      await this.refit();
      return performance.now() - started;
    }
    const flat = topLevel.flat;
    this.prepared.instanceBounds = flat.instanceBounds;
    this.prepared.placementTransforms = { base: flat.placementTransformBase, records: flat.placementTransforms };
    this.writePlacementTransforms(flat.placementTransforms);
    if (this.mode === 'gpu' || how === 'refit') {
      this.prepared.primitives = packPrimitives(flat, this.prepared.acceleration.order ?? identity(flat.count));
      queue.writeBuffer(target, 0, this.prepared.primitives);
      if (how === 'refit') await this.refit();
      else await this.buildOnGpu();
      return performance.now() - started;
    }
    const bvh = await buildBvhAsync(flat.boundsTriangles);
    const nodes = packWavefrontBvhNodes(bvh);
    this.prepared.primitives = packPrimitives(flat, bvh.triangleOrder);
    queue.writeBuffer(this.buffers.primitives, 0, this.prepared.primitives);
    queue.writeBuffer(this.buffers.bvhNodes, 0, nodes);
    queue.writeBuffer(this.buffers.bvhParents, 0, bvhParentLinks(nodes, bvh.nodeCount));
    this.prepared.acceleration.order = bvh.triangleOrder;
    this.prepared.bvh = { nodeCount: bvh.nodeCount, depth: bvh.depth, sahCost: bvh.sahCost, buildTimeMs: bvh.buildTimeMs };
    // The refitter's node count belongs to the old tree.
    this.refitter?.destroy();
    this.refitter = null;
    await queue.onSubmittedWorkDone();
    return performance.now() - started;
  }

  /** Recomputes every box of the uploaded tree on the GPU (its topology kept). */
  private async refit(): Promise<void> {
    if (this.mode === 'gpu') {
      await this.builder!.refit();
      return;
    }
    this.refitter ??= await GpuBvhRefitter.create(this.device, { nodes: this.buffers.bvhNodes, parents: this.buffers.bvhParents, primitives: this.buffers.primitives, nodeCount: this.prepared.bvh.nodeCount });
    await this.refitter.refit();
  }

  destroy(): void {
    this.builder?.destroy();
    this.refitter?.destroy();
    // The scene-order records (a scene replaced by updateScene gets a new acceleration).
    if (this.source) this.owner?.release(this.source);
  }
}
