import {
  INDEX_NONE,
  VERTEX_COLOR_WORDS,
  VERTEX_NORMAL_INVALID,
  VERTEX_NORMAL_WORDS,
  VERTEX_POSITION_WORDS,
  VERTEX_TANGENT_WORDS,
  VERTEX_UV_WORDS,
} from '../../gpu-layout/constants.ts';
import { encodeOctahedralSnorm16 } from '../../gpu-layout/octahedral.ts';
import type { NormalizedMesh } from '../../scene/mesh.ts';

/** Word offsets of one mesh's streams in `vertexStreams`; INDEX_NONE for an attribute it lacks. */
export interface MeshStreamOffsets {
  positions: number;
  normals: number;
  tangents: number;
  colors: number;
  uv0: number;
  uv1: number;
}

/**
 * Every mesh's vertex attributes as separate streams (one per attribute the mesh has) laid end to
 * end in one u32 buffer, and its triangles in one index buffer of mesh-local vertex numbers.
 * Separate streams let a hit read only what it shades with: three normals of one word each share
 * cache lines, where interleaved vertices would cost a line per vertex. A raster pass binds the
 * same buffer as vertex buffers at the stream offsets.
 */
export interface PackedVertexStreams {
  vertexStreams: Uint32Array;
  indices: Uint32Array;
  /** Per mesh: where its streams start. */
  streams: MeshStreamOffsets[];
  /** Per mesh: its first index in `indices`. */
  firstIndex: number[];
  vertexCount: number;
}

/** Words per vertex of a mesh's streams. */
function wordsPerVertex(m: NormalizedMesh): number {
  return (
    VERTEX_POSITION_WORDS +
    (m.normals ? VERTEX_NORMAL_WORDS : 0) +
    (m.tangents ? VERTEX_TANGENT_WORDS : 0) +
    (m.colors ? VERTEX_COLOR_WORDS : 0) +
    (m.uvs ? VERTEX_UV_WORDS : 0) +
    (m.uvs1 ? VERTEX_UV_WORDS : 0)
  );
}

/** Sizes of the two buffers, known before anything is packed (the buffer plan checks them). */
export function vertexStreamBytes(meshes: readonly NormalizedMesh[]): { vertexStreams: number; indices: number } {
  let words = 0;
  let indices = 0;
  for (const m of meshes) {
    words += m.vertexCount * wordsPerVertex(m);
    indices += m.indices.length;
  }
  return { vertexStreams: Math.max(1, words) * 4, indices: Math.max(1, indices) * 4 };
}

function packColor(c: Float32Array, v: number): number {
  const q = (x: number): number => Math.round(Math.min(1, Math.max(0, x)) * 255);
  return (q(c[4 * v]!) | (q(c[4 * v + 1]!) << 8) | (q(c[4 * v + 2]!) << 16) | (q(c[4 * v + 3]!) << 24)) >>> 0;
}

export function packVertexStreams(meshes: readonly NormalizedMesh[]): PackedVertexStreams {
  const { vertexStreams: bytes } = vertexStreamBytes(meshes);
  const words = new Uint32Array(bytes / 4);
  const floats = new Float32Array(words.buffer);
  const indexTotal = meshes.reduce((n, m) => n + m.indices.length, 0);
  const indices = new Uint32Array(Math.max(1, indexTotal));
  const streams: MeshStreamOffsets[] = [];
  const firstIndex: number[] = [];
  let cursor = 0;
  let i0 = 0;
  // Reserves a stream of `perVertex` words for `n` vertices and returns its offset.
  const reserve = (n: number, perVertex: number): number => {
    const at = cursor;
    cursor += n * perVertex;
    return at;
  };
  for (const mesh of meshes) {
    const n = mesh.vertexCount;
    const s: MeshStreamOffsets = {
      positions: reserve(n, VERTEX_POSITION_WORDS),
      normals: mesh.normals ? reserve(n, VERTEX_NORMAL_WORDS) : INDEX_NONE,
      tangents: mesh.tangents ? reserve(n, VERTEX_TANGENT_WORDS) : INDEX_NONE,
      colors: mesh.colors ? reserve(n, VERTEX_COLOR_WORDS) : INDEX_NONE,
      uv0: mesh.uvs ? reserve(n, VERTEX_UV_WORDS) : INDEX_NONE,
      uv1: mesh.uvs1 ? reserve(n, VERTEX_UV_WORDS) : INDEX_NONE,
    };
    streams.push(s);
    firstIndex.push(i0);
    indices.set(mesh.indices, i0);
    floats.set(mesh.positions.subarray(0, 3 * n), s.positions);
    if (mesh.normals) {
      for (let v = 0; v < n; v++) {
        const x = mesh.normals[3 * v]!, y = mesh.normals[3 * v + 1]!, z = mesh.normals[3 * v + 2]!;
        words[s.normals + v] = Math.hypot(x, y, z) > 1e-12 ? encodeOctahedralSnorm16([x, y, z]) : VERTEX_NORMAL_INVALID;
      }
    }
    if (mesh.tangents) {
      for (let v = 0; v < n; v++) {
        const t = mesh.tangents;
        words[s.tangents + 2 * v] = encodeOctahedralSnorm16([t[4 * v]!, t[4 * v + 1]!, t[4 * v + 2]!]);
        floats[s.tangents + 2 * v + 1] = t[4 * v + 3]! < 0 ? -1 : 1;
      }
    }
    if (mesh.colors) {
      for (let v = 0; v < n; v++) words[s.colors + v] = packColor(mesh.colors, v);
    }
    if (mesh.uvs) floats.set(mesh.uvs.subarray(0, 2 * n), s.uv0);
    if (mesh.uvs1) floats.set(mesh.uvs1.subarray(0, 2 * n), s.uv1);
    i0 += mesh.indices.length;
  }
  return { vertexStreams: words, indices, streams, firstIndex, vertexCount: meshes.reduce((n, m) => n + m.vertexCount, 0) };
}
