import { vertexLayout } from '../../gpu-layout/records.ts';
import { VERTEX_FLAG_BITANGENT_NEGATIVE, VERTEX_FLAG_NORMAL_INVALID } from '../../gpu-layout/constants.ts';
import { encodeOctahedralSnorm16 } from '../../gpu-layout/octahedral.ts';
import type { NormalizedMesh } from '../../scene/mesh.ts';

/** Every mesh's vertex streams in one `Vertex` buffer and its triangles in one index buffer. */
export interface PackedVertexStreams {
  vertices: ArrayBuffer;
  indices: Uint32Array;
  /** Per mesh: its first vertex and first index in the shared buffers. */
  baseVertex: number[];
  firstIndex: number[];
  vertexCount: number;
}

const W = Object.fromEntries(vertexLayout.fields.map((f) => [f.name, f.offset / 4])) as Record<string, number>;
const WORDS = vertexLayout.size / 4;

export function vertexStreamBytes(meshes: readonly NormalizedMesh[]): { vertices: number; indices: number } {
  let vertices = 0;
  let indices = 0;
  for (const m of meshes) {
    vertices += m.vertexCount;
    indices += m.indices.length;
  }
  return { vertices: Math.max(1, vertices) * vertexLayout.size, indices: Math.max(1, indices) * 4 };
}

function packColor(c: Float32Array, v: number): number {
  const q = (x: number): number => Math.round(Math.min(1, Math.max(0, x)) * 255);
  return (q(c[4 * v]!) | (q(c[4 * v + 1]!) << 8) | (q(c[4 * v + 2]!) << 16) | (q(c[4 * v + 3]!) << 24)) >>> 0;
}

export function packVertexStreams(meshes: readonly NormalizedMesh[]): PackedVertexStreams {
  const total = meshes.reduce((n, m) => n + m.vertexCount, 0);
  const indexTotal = meshes.reduce((n, m) => n + m.indices.length, 0);
  const vertices = new ArrayBuffer(Math.max(1, total) * vertexLayout.size);
  const f = new Float32Array(vertices);
  const u = new Uint32Array(vertices);
  const indices = new Uint32Array(Math.max(1, indexTotal));
  const baseVertex: number[] = [];
  const firstIndex: number[] = [];
  let v0 = 0;
  let i0 = 0;
  for (const mesh of meshes) {
    baseVertex.push(v0);
    firstIndex.push(i0);
    indices.set(mesh.indices, i0);
    for (let v = 0; v < mesh.vertexCount; v++) {
      const o = (v0 + v) * WORDS;
      f[o + W.position!] = mesh.positions[3 * v]!;
      f[o + W.position! + 1] = mesh.positions[3 * v + 1]!;
      f[o + W.position! + 2] = mesh.positions[3 * v + 2]!;
      let flags = 0;
      if (mesh.normals) {
        const n = [mesh.normals[3 * v]!, mesh.normals[3 * v + 1]!, mesh.normals[3 * v + 2]!];
        if (Math.hypot(n[0]!, n[1]!, n[2]!) > 1e-12) u[o + W.normal!] = encodeOctahedralSnorm16(n);
        else flags |= VERTEX_FLAG_NORMAL_INVALID;
      }
      if (mesh.tangents) {
        u[o + W.tangent!] = encodeOctahedralSnorm16([mesh.tangents[4 * v]!, mesh.tangents[4 * v + 1]!, mesh.tangents[4 * v + 2]!]);
        if (mesh.tangents[4 * v + 3]! < 0) flags |= VERTEX_FLAG_BITANGENT_NEGATIVE;
      }
      u[o + W.flags!] = flags;
      u[o + W.color!] = mesh.colors ? packColor(mesh.colors, v) : 0xffffffff;
      if (mesh.uvs) {
        f[o + W.uv0!] = mesh.uvs[2 * v]!;
        f[o + W.uv0! + 1] = mesh.uvs[2 * v + 1]!;
      }
      if (mesh.uvs1) {
        f[o + W.uv1!] = mesh.uvs1[2 * v]!;
        f[o + W.uv1! + 1] = mesh.uvs1[2 * v + 1]!;
      }
    }
    v0 += mesh.vertexCount;
    i0 += mesh.indices.length;
  }
  return { vertices, indices, baseVertex, firstIndex, vertexCount: total };
}
