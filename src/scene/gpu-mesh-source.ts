import { normalizeWavefrontMesh, type NormalizedMesh } from './mesh.ts';
import type { NormalizedMaterial } from './material.ts';
import type { WavefrontMeshInput } from './types.ts';

/**
 * Meshes flattened into per-triangle arrays, the form the BVH builder and the GPU packers consume.
 * Triangle t owns positions[9t..9t+9), normals[9t..9t+9) and uvs[6t..6t+6).
 */
export interface WavefrontGpuMeshSource {
  triangleCount: number;
  positions: Float32Array;
  /** Per-vertex normals, or the geometric normal where a mesh has none. */
  normals: Float32Array;
  uvs: Float32Array;
  hasNormals: Uint8Array;
  hasUvs: Uint8Array;
  materialIds: Uint32Array;
  meshIndices: Uint32Array;
  /** One material per mesh, indexed by materialIds. */
  materials: NormalizedMaterial[];
  meshes: NormalizedMesh[];
}

function isNormalized(m: WavefrontMeshInput | NormalizedMesh): m is NormalizedMesh {
  return (m as NormalizedMesh).positions instanceof Float32Array && (m as NormalizedMesh).indices instanceof Uint32Array && 'triangleCount' in m;
}

export function createWavefrontGpuMeshSource(meshes: readonly (WavefrontMeshInput | NormalizedMesh)[]): WavefrontGpuMeshSource {
  const normalized = meshes.map((m, i) => (isNormalized(m) ? m : normalizeWavefrontMesh(m, i)));
  const triangleCount = normalized.reduce((n, m) => n + m.triangleCount, 0);
  const positions = new Float32Array(triangleCount * 9);
  const normals = new Float32Array(triangleCount * 9);
  const uvs = new Float32Array(triangleCount * 6);
  const hasNormals = new Uint8Array(triangleCount);
  const hasUvs = new Uint8Array(triangleCount);
  const materialIds = new Uint32Array(triangleCount);
  const meshIndices = new Uint32Array(triangleCount);
  let t = 0;
  normalized.forEach((mesh, meshIndex) => {
    const { positions: p, indices, normals: n, uvs: uv } = mesh;
    for (let k = 0; k < mesh.triangleCount; k++, t++) {
      for (let c = 0; c < 3; c++) {
        const vi = indices[3 * k + c]!;
        positions[9 * t + 3 * c] = p[3 * vi]!;
        positions[9 * t + 3 * c + 1] = p[3 * vi + 1]!;
        positions[9 * t + 3 * c + 2] = p[3 * vi + 2]!;
        if (n) {
          normals[9 * t + 3 * c] = n[3 * vi]!;
          normals[9 * t + 3 * c + 1] = n[3 * vi + 1]!;
          normals[9 * t + 3 * c + 2] = n[3 * vi + 2]!;
        }
        if (uv) {
          uvs[6 * t + 2 * c] = uv[2 * vi]!;
          uvs[6 * t + 2 * c + 1] = uv[2 * vi + 1]!;
        }
      }
      const ng = geometricNormal(positions, t);
      // Missing or degenerate vertex normals fall back to the geometric normal.
      let ok = n !== null;
      if (ok) {
        for (let c = 0; c < 3; c++) {
          const len = Math.hypot(normals[9 * t + 3 * c]!, normals[9 * t + 3 * c + 1]!, normals[9 * t + 3 * c + 2]!);
          if (!(len > 1e-12)) ok = false;
        }
      }
      if (!ok) for (let c = 0; c < 3; c++) normals.set(ng, 9 * t + 3 * c);
      hasNormals[t] = ok ? 1 : 0;
      hasUvs[t] = uv ? 1 : 0;
      materialIds[t] = meshIndex;
      meshIndices[t] = meshIndex;
    }
  });
  return { triangleCount, positions, normals, uvs, hasNormals, hasUvs, materialIds, meshIndices, materials: normalized.map((m) => m.material), meshes: normalized };
}

/** Unit cross(v1 - v0, v2 - v0) of triangle t: the front face is counter-clockwise. Zero for degenerate triangles. */
export function geometricNormal(positions: Float32Array, t: number): [number, number, number] {
  const o = 9 * t;
  const e1x = positions[o + 3]! - positions[o]!, e1y = positions[o + 4]! - positions[o + 1]!, e1z = positions[o + 5]! - positions[o + 2]!;
  const e2x = positions[o + 6]! - positions[o]!, e2y = positions[o + 7]! - positions[o + 1]!, e2z = positions[o + 8]! - positions[o + 2]!;
  const cx = e1y * e2z - e1z * e2y, cy = e1z * e2x - e1x * e2z, cz = e1x * e2y - e1y * e2x;
  const len = Math.hypot(cx, cy, cz);
  return len > 0 ? [cx / len, cy / len, cz / len] : [0, 0, 0];
}

export function triangleArea(positions: Float32Array, t: number): number {
  const o = 9 * t;
  const e1x = positions[o + 3]! - positions[o]!, e1y = positions[o + 4]! - positions[o + 1]!, e1z = positions[o + 5]! - positions[o + 2]!;
  const e2x = positions[o + 6]! - positions[o]!, e2y = positions[o + 7]! - positions[o + 1]!, e2z = positions[o + 8]! - positions[o + 2]!;
  return 0.5 * Math.hypot(e1y * e2z - e1z * e2y, e1z * e2x - e1x * e2z, e1x * e2y - e1y * e2x);
}
