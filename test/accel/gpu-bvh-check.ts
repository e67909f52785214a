// Runs the GPU BVH builder on real WebGPU and checks what it wrote on the CPU, independently of the
// builder's own figures: the shared plumbing of the GPU BVH tests.
import assert from 'node:assert/strict';
import { GpuBvhBuilder, type GpuBvhBuildOptions, type GpuBvhBuildResult } from '../../src/accel/gpu-build/gpu-bvh-builder.ts';
import { computeSahCost } from '../../src/accel/bvh-sah.ts';
import { packWavefrontTriangles } from '../../src/accel/triangle-packing.ts';
import { INDEX_NONE, PRIMITIVE_SHAPE_BOX, PRIMITIVE_SHAPE_MASK, PRIMITIVE_SHAPE_SPHERE } from '../../src/gpu-layout/constants.ts';
import { bvhNodeLayout, primitiveLayout } from '../../src/gpu-layout/records.ts';
import { BufferUsage } from '../../src/gpu/webgpu-constants.ts';
import { readBuffer, testDevice, uploadBuffer } from '../helpers/gpu.ts';

const PW = primitiveLayout.size / 4;

export interface GpuBuild {
  result: GpuBvhBuildResult;
  nodes: ArrayBuffer;
  parents: Uint32Array;
  /** Primitive records in BVH slot order, as the GPU wrote them. */
  primitives: ArrayBuffer;
  /** The scene-order records the build read. */
  source: ArrayBuffer;
  builder: GpuBvhBuilder;
  buffers: { source: GPUBuffer; primitives: GPUBuffer; nodes: GPUBuffer; parents: GPUBuffer };
}

/** Scene-order primitive records of a triangle soup (instance 0, primitive = triangle index). */
export function sourceRecords(triangles: Float32Array): ArrayBuffer {
  const n = triangles.length / 9;
  return packWavefrontTriangles(triangles, Uint32Array.from({ length: n }, (_, i) => i));
}

export function buildOnGpu(triangles: Float32Array, options: GpuBvhBuildOptions = {}): Promise<GpuBuild> {
  return buildRecordsOnGpu(sourceRecords(triangles), options);
}

/** Builds over scene-order primitive records of any shape. */
export async function buildRecordsOnGpu(source: ArrayBuffer, options: GpuBvhBuildOptions = {}): Promise<GpuBuild> {
  const device = await testDevice();
  const n = source.byteLength / primitiveLayout.size;
  const S = BufferUsage.STORAGE | BufferUsage.COPY_SRC | BufferUsage.COPY_DST;
  const buffers = {
    source: uploadBuffer(device, source),
    primitives: device.createBuffer({ size: n * primitiveLayout.size, usage: S }),
    nodes: device.createBuffer({ size: (2 * n - 1) * bvhNodeLayout.size, usage: S }),
    parents: device.createBuffer({ size: Math.max(16, (2 * n - 1) * 4), usage: S }),
  };
  const builder = await GpuBvhBuilder.create(device, { ...buffers, primitiveCount: n }, options);
  const result = await builder.build();
  return { result, source, builder, buffers, ...(await readTree(buffers, result.nodeCount, n)) };
}

export async function readTree(buffers: GpuBuild['buffers'], nodeCount: number, n: number): Promise<Pick<GpuBuild, 'nodes' | 'parents' | 'primitives'>> {
  const device = await testDevice();
  return {
    nodes: await readBuffer(device, buffers.nodes, nodeCount * bvhNodeLayout.size),
    parents: new Uint32Array(await readBuffer(device, buffers.parents, Math.max(4, nodeCount * 4)), 0, nodeCount),
    primitives: await readBuffer(device, buffers.primitives, n * primitiveLayout.size),
  };
}

export function destroyBuild(b: GpuBuild): void {
  b.builder.destroy();
  for (const buffer of Object.values(b.buffers)) buffer.destroy();
}

/**
 * f32 box of one primitive record as the traversal sees it: triangle v0, v0 + e1, v0 + e2; sphere
 * v0 +- e1.x; box v0 .. e1.
 */
export function recordBox(f: Float32Array, slot: number): number[] {
  const o = slot * PW;
  const kind = new Uint32Array(f.buffer, f.byteOffset, f.length)[o + 11]! & PRIMITIVE_SHAPE_MASK;
  if (kind === PRIMITIVE_SHAPE_SPHERE) {
    const r = f[o + 4]!;
    return [0, 1, 2, 0, 1, 2].map((c, i) => Math.fround(i < 3 ? f[o + c]! - r : f[o + c]! + r));
  }
  if (kind === PRIMITIVE_SHAPE_BOX) return [f[o]!, f[o + 1]!, f[o + 2]!, f[o + 4]!, f[o + 5]!, f[o + 6]!];
  const box = [Infinity, Infinity, Infinity, -Infinity, -Infinity, -Infinity];
  for (let v = 0; v < 3; v++) {
    for (let c = 0; c < 3; c++) {
      const x = v === 0 ? f[o + c]! : Math.fround(f[o + c]! + f[o + 4 * v + c]!);
      box[c] = Math.min(box[c]!, x);
      box[3 + c] = Math.max(box[3 + c]!, x);
    }
  }
  return box;
}

export interface TreeStats {
  depth: number;
  leaves: number;
  maxLeaf: number;
  /** Nodes whose box is exactly the union of its children's (interior) or primitives' (leaf). */
  tight: number;
}

/**
 * Every promise the traversal relies on, checked by walking the tree from the root: each node
 * reached once, every node reachable, interior children adjacent and inside their parent's box,
 * parent links, every primitive slot in exactly one leaf and inside its box, and the records in
 * BVH order being exactly the source records (each once). Returns what it saw.
 */
export function checkGpuTree(b: Pick<GpuBuild, 'nodes' | 'parents' | 'primitives' | 'source'>, nodeCount: number): TreeStats {
  const f = new Float32Array(b.nodes);
  const u = new Uint32Array(b.nodes);
  const src = new Uint32Array(b.source);
  const out = new Uint32Array(b.primitives);
  const outF = new Float32Array(b.primitives);
  const n = src.length / PW;
  assert.equal(out.length / PW, n);
  // The BVH-order records are a permutation of the source records (primitive = source index).
  const seen = new Uint8Array(n);
  for (let s = 0; s < n; s++) {
    const k = out[s * PW + 7]!;
    assert.ok(k < n, `slot ${s} holds primitive ${k} >= ${n}`);
    assert.equal(seen[k], 0, `primitive ${k} appears twice`);
    seen[k] = 1;
    for (let w = 0; w < PW; w++) assert.equal(out[s * PW + w], src[k * PW + w], `slot ${s} is not a copy of source record ${k}`);
  }
  const box = (i: number): number[] => [f[i * 8]!, f[i * 8 + 1]!, f[i * 8 + 2]!, f[i * 8 + 4]!, f[i * 8 + 5]!, f[i * 8 + 6]!];
  const visited = new Uint8Array(nodeCount);
  const covered = new Uint8Array(n);
  const stats: TreeStats = { depth: 0, leaves: 0, maxLeaf: 0, tight: 0 };
  assert.equal(b.parents[0], INDEX_NONE, 'the root has no parent');
  const stack: [number, number][] = [[0, 0]];
  while (stack.length > 0) {
    const [node, depth] = stack.pop()!;
    assert.ok(node < nodeCount, `node ${node} out of range`);
    assert.equal(visited[node], 0, `node ${node} reached twice`);
    visited[node] = 1;
    const nb = box(node);
    const first = u[node * 8 + 3]!;
    const count = u[node * 8 + 7]!;
    const union = [Infinity, Infinity, Infinity, -Infinity, -Infinity, -Infinity];
    const grow = (c: number[]): void => {
      for (let a = 0; a < 3; a++) {
        union[a] = Math.min(union[a]!, c[a]!);
        union[3 + a] = Math.max(union[3 + a]!, c[3 + a]!);
      }
    };
    const inside = (c: number[], what: string): void => {
      for (let a = 0; a < 3; a++) assert.ok(c[a]! >= nb[a]! && c[3 + a]! <= nb[3 + a]!, `${what} sticks out of node ${node}`);
    };
    if (count > 0) {
      stats.leaves++;
      stats.depth = Math.max(stats.depth, depth);
      stats.maxLeaf = Math.max(stats.maxLeaf, count);
      for (let s = first; s < first + count; s++) {
        assert.ok(s < n, `leaf ${node} reaches slot ${s} >= ${n}`);
        assert.equal(covered[s], 0, `slot ${s} in two leaves`);
        covered[s] = 1;
        const pb = recordBox(outF, s);
        inside(pb, `slot ${s}`);
        grow(pb);
      }
    } else {
      assert.ok(first >= 1 && first + 1 < nodeCount, `interior ${node} has children ${first}, ${first + 1}`);
      for (const child of [first, first + 1]) {
        assert.equal(b.parents[child], node, `parent link of ${child}`);
        inside(box(child), `child ${child}`);
        grow(box(child));
      }
      stack.push([first + 1, depth + 1], [first, depth + 1]);
    }
    if (union.every((x, i) => x === nb[i])) stats.tight++;
  }
  assert.ok(visited.every((v) => v === 1), 'every node is reachable from the root');
  assert.ok(covered.every((v) => v === 1), 'every primitive slot belongs to exactly one leaf');
  return stats;
}

/** Checks the tree and that the builder's own figures agree with it. */
export function checkBuild(b: GpuBuild): TreeStats {
  const stats = checkGpuTree(b, b.result.nodeCount);
  assert.equal(b.result.depth, stats.depth, 'reported depth');
  assert.equal(b.result.leafCount, stats.leaves, 'reported leaf count');
  const sah = computeSahCost(b.nodes, { nodeCount: b.result.nodeCount });
  assert.ok(Math.abs(b.result.sahCost - sah) <= 1e-4 * sah, `reported SAH ${b.result.sahCost} vs ${sah} recomputed from the nodes`);
  return stats;
}
