/**
 * GPU skinning of the skinned instances: every skinned mesh's bind-pose streams, influences and
 * morph deltas live in shared read-only buffers; every skinned instance owns a joint-matrix range, a
 * morph-weight range and output streams (positions, normals, tangents) that the draw passes bind as
 * vertex buffers. One compute dispatch per instance per frame (skin.wesl).
 */
import { allocateStructArray, writeStruct } from '../../gpu-layout/struct-layout.ts';
import { BufferUsage } from '../../gpu/webgpu-constants.ts';
import type { RasterSkinnedMesh } from '../scene/raster-scene.ts';
import type { RasterPipelines } from './pipelines.ts';
import { rasterConstants, rasterSkinParamsLayout } from './raster-layout.ts';

const PARAMS_STRIDE = 256;

export interface SkinnedInstanceGpu {
  readonly mesh: number;
  readonly vertexCount: number;
  readonly jointCount: number;
  readonly targetCount: number;
  /** Byte offsets of the output streams in `output`. */
  readonly positions: number;
  readonly normals: number | null;
  readonly tangents: number | null;
}

export interface RasterSkinning {
  readonly output: GPUBuffer;
  readonly instances: readonly SkinnedInstanceGpu[];
  readonly skinnedVertexCount: number;
  setPose(index: number, jointMatrices: ArrayLike<number>, morphWeights?: ArrayLike<number>): void;
  /** Records the skinning dispatches (a no-op without skinned instances). */
  encode(pass: GPUComputePassEncoder): void;
  readonly bytes: number;
  destroy(): void;
}

export function createRasterSkinning(device: GPUDevice, pipelines: RasterPipelines, meshes: readonly RasterSkinnedMesh[], instanceMeshes: readonly number[]): RasterSkinning {
  // Shared sources: per mesh, positions, normals, tangents, then the target blocks.
  const source: number[] = [];
  const influences: number[] = [];
  const meshInfo = meshes.map((m) => {
    const n = m.mesh.vertexCount;
    const positions = source.length;
    for (const x of m.mesh.positions) source.push(x);
    const normals = source.length;
    if (m.mesh.normals) for (const x of m.mesh.normals) source.push(x);
    const tangents = source.length;
    if (m.mesh.tangents) for (const x of m.mesh.tangents) source.push(x);
    const targets = source.length;
    for (const block of m.targets) for (const x of block) source.push(x);
    const influenceOffset = influences.length;
    if (m.influences > 0) {
      const f = new Float32Array(1);
      const u = new Uint32Array(f.buffer);
      for (let v = 0; v < n; v++) {
        for (let k = 0; k < m.influences; k++) influences.push(m.joints![m.influences * v + k]!);
        for (let k = 0; k < m.influences; k++) {
          f[0] = m.weights![m.influences * v + k]!;
          influences.push(u[0]!);
        }
      }
    }
    return { positions, normals, tangents, targets, influenceOffset };
  });
  let jointTotal = 0;
  let weightTotal = 0;
  let outWords = 0;
  let skinnedVertexCount = 0;
  const instances: (SkinnedInstanceGpu & { jointOffset: number; weightOffset: number })[] = instanceMeshes.map((mi) => {
    const m = meshes[mi]!;
    const n = m.mesh.vertexCount;
    const reserve = (words: number): number => {
      const at = outWords;
      outWords += words;
      return at * 4;
    };
    const inst = {
      mesh: mi,
      vertexCount: n,
      jointCount: m.jointCount,
      targetCount: m.targets.length,
      jointOffset: jointTotal,
      weightOffset: weightTotal,
      positions: reserve(3 * n),
      normals: m.mesh.normals ? reserve(3 * n) : null,
      tangents: m.mesh.tangents ? reserve(4 * n) : null,
    };
    jointTotal += m.jointCount;
    weightTotal += m.targets.length;
    skinnedVertexCount += n;
    return inst;
  });
  const storage = (label: string, data: ArrayBufferView | null, bytes: number, usage = 0): GPUBuffer => {
    const buffer = device.createBuffer({ label, size: Math.max(16, Math.ceil(bytes / 4) * 4), usage: BufferUsage.STORAGE | BufferUsage.COPY_DST | usage });
    if (data !== null && data.byteLength > 0) device.queue.writeBuffer(buffer, 0, data.buffer, data.byteOffset, data.byteLength);
    return buffer;
  };
  const sourceBuffer = storage('raster skin source', Float32Array.from(source), 4 * source.length);
  const influenceBuffer = storage('raster skin influences', Uint32Array.from(influences), 4 * influences.length);
  const joints = storage('raster joint matrices', null, 64 * jointTotal);
  const weights = storage('raster morph weights', null, 4 * weightTotal);
  const output = storage('raster skinned vertices', null, 4 * outWords, BufferUsage.VERTEX | BufferUsage.COPY_SRC);
  const params = new ArrayBuffer(Math.max(1, instances.length) * PARAMS_STRIDE);
  const one = allocateStructArray(rasterSkinParamsLayout, 1);
  instances.forEach((inst, i) => {
    const m = meshes[inst.mesh]!;
    const info = meshInfo[inst.mesh]!;
    let flags = 0;
    if (inst.normals !== null) flags |= rasterConstants.SKIN_HAS_NORMALS;
    if (inst.tangents !== null) flags |= rasterConstants.SKIN_HAS_TANGENTS;
    if (m.influences > 0) flags |= rasterConstants.SKIN_IS_SKINNED;
    writeStruct(rasterSkinParamsLayout, new DataView(one), 0, {
      vertexCount: inst.vertexCount,
      influences: m.influences,
      targetCount: inst.targetCount,
      flags,
      positions: info.positions,
      normals: info.normals,
      tangents: info.tangents,
      targets: info.targets,
      influenceOffset: info.influenceOffset,
      jointOffset: inst.jointOffset,
      weightOffset: inst.weightOffset,
      outPositions: inst.positions / 4,
      outNormals: (inst.normals ?? 0) / 4,
      outTangents: (inst.tangents ?? 0) / 4,
      jointCount: inst.jointCount,
    });
    new Uint8Array(params, i * PARAMS_STRIDE, one.byteLength).set(new Uint8Array(one));
  });
  const paramsBuffer = device.createBuffer({ label: 'raster skin params', size: params.byteLength, usage: BufferUsage.UNIFORM | BufferUsage.COPY_DST });
  device.queue.writeBuffer(paramsBuffer, 0, params);
  const bindGroup = device.createBindGroup({
    label: 'raster skinning',
    layout: pipelines.skinLayout,
    entries: [
      { binding: 0, resource: { buffer: paramsBuffer, size: rasterSkinParamsLayout.size } },
      { binding: 1, resource: { buffer: sourceBuffer } },
      { binding: 2, resource: { buffer: influenceBuffer } },
      { binding: 3, resource: { buffer: joints } },
      { binding: 4, resource: { buffer: weights } },
      { binding: 5, resource: { buffer: output } },
    ],
  });
  // Until a pose is set, every joint matrix is the identity and every morph weight 0 (bind pose).
  const identity = new Float32Array(16 * Math.max(1, jointTotal));
  for (let j = 0; j < jointTotal; j++) for (let d = 0; d < 4; d++) identity[16 * j + 5 * d] = 1;
  if (jointTotal > 0) device.queue.writeBuffer(joints, 0, identity);
  const bytes = [sourceBuffer, influenceBuffer, joints, weights, output, paramsBuffer].reduce((s, b) => s + b.size, 0);
  return {
    output,
    instances,
    skinnedVertexCount,
    bytes,
    setPose(index, jointMatrices, morphWeights) {
      const inst = instances[index]!;
      if (inst.jointCount > 0) {
        const data = Float32Array.from({ length: 16 * inst.jointCount }, (_, i) => jointMatrices[i] ?? 0);
        device.queue.writeBuffer(joints, 64 * inst.jointOffset, data);
      }
      if (inst.targetCount > 0 && morphWeights !== undefined) {
        const data = Float32Array.from({ length: inst.targetCount }, (_, i) => morphWeights[i] ?? 0);
        device.queue.writeBuffer(weights, 4 * inst.weightOffset, data);
      }
    },
    encode(pass) {
      if (instances.length === 0) return;
      pass.setPipeline(pipelines.compute('skin'));
      instances.forEach((inst, i) => {
        pass.setBindGroup(0, bindGroup, [i * PARAMS_STRIDE]);
        pass.dispatchWorkgroups(Math.ceil(inst.vertexCount / rasterConstants.SKIN_WORKGROUP_SIZE));
      });
    },
    destroy() {
      for (const b of [sourceBuffer, influenceBuffer, joints, weights, output, paramsBuffer]) b.destroy();
    },
  };
}
