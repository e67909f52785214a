import { buildBvh, buildBvhAsync, packWavefrontBvhNodes, packWavefrontTriangles, type BvhBuildResult } from '../accel/index.ts';

import { TRIANGLE_FLAG_HAS_NORMALS, TRIANGLE_FLAG_HAS_UVS, triangleAttributesLayout } from '../gpu-layout/records.ts';
import { encodeOctahedralSnorm16 } from '../gpu-layout/octahedral.ts';
import { buildEmissiveLightTable, type EmissiveLightTable } from '../lighting/emissive-lights.ts';
import { createWavefrontGpuMeshSource, geometricNormal, triangleArea, type WavefrontGpuMeshSource } from '../scene/gpu-mesh-source.ts';
import { isEmissive } from '../scene/material.ts';
import type { NormalizedMesh } from '../scene/mesh.ts';
import type { WavefrontMeshInput } from '../scene/types.ts';

/** Meshes ready for the GPU: BVH-ordered triangles and attributes, BVH nodes and the light table. */
export interface WavefrontMeshAcceleration {
  source: WavefrontGpuMeshSource;
  triangleCount: number;
  nodeCount: number;
  bvhDepth: number;
  sahCost: number;
  buildTimeMs: number;
  triangleOrder: Uint32Array;
  triangles: ArrayBuffer;
  attributes: ArrayBuffer;
  nodes: ArrayBuffer;
  lights: EmissiveLightTable;
  bounds: { min: [number, number, number]; max: [number, number, number] };
}

const A = Object.fromEntries(triangleAttributesLayout.fields.map((f) => [f.name, f.offset / 4])) as Record<string, number>;
const ATTR_WORDS = triangleAttributesLayout.size / 4;

function packAttributes(source: WavefrontGpuMeshSource, order: Uint32Array, areas: Float32Array, pmfBySlot: Map<number, number>): ArrayBuffer {
  const buffer = new ArrayBuffer(Math.max(1, order.length) * triangleAttributesLayout.size);
  const f = new Float32Array(buffer);
  const u = new Uint32Array(buffer);
  for (let s = 0; s < order.length; s++) {
    const t = order[s]!;
    const o = s * ATTR_WORDS;
    for (let c = 0; c < 3; c++) {
      const at = o + A[`n${c}`]!;
      f[at] = source.normals[9 * t + 3 * c]!;
      f[at + 1] = source.normals[9 * t + 3 * c + 1]!;
      f[at + 2] = source.normals[9 * t + 3 * c + 2]!;
      const uvAt = o + A[`uv${c}`]!;
      f[uvAt] = source.uvs[6 * t + 2 * c]!;
      f[uvAt + 1] = source.uvs[6 * t + 2 * c + 1]!;
    }
    f[o + A.lightPmf!] = pmfBySlot.get(s) ?? 0;
    f[o + A.area!] = areas[t]!;
    u[o + A.flags!] = (source.hasNormals[t] ? TRIANGLE_FLAG_HAS_NORMALS : 0) | (source.hasUvs[t] ? TRIANGLE_FLAG_HAS_UVS : 0);
    u[o + A.geometricNormal!] = encodeOctahedralSnorm16(geometricNormal(source.positions, t));
    u[o + A.materialId!] = source.materialIds[t]!;
  }
  return buffer;
}

function finish(source: WavefrontGpuMeshSource, bvh: BvhBuildResult): WavefrontMeshAcceleration {
  const order = bvh.triangleOrder;
  const p = source.positions;
  const areas = new Float32Array(source.triangleCount);
  for (let t = 0; t < source.triangleCount; t++) areas[t] = triangleArea(p, t);
  const emissive = [];
  for (let s = 0; s < order.length; s++) {
    const t = order[s]!;
    const material = source.materials[source.materialIds[t]!]!;
    if (!isEmissive(material)) continue;
    emissive.push({
      triangle: s,
      v0: [p[9 * t]!, p[9 * t + 1]!, p[9 * t + 2]!],
      v1: [p[9 * t + 3]!, p[9 * t + 4]!, p[9 * t + 5]!],
      v2: [p[9 * t + 6]!, p[9 * t + 7]!, p[9 * t + 8]!],
      area: areas[t]!,
      emission: material.emission,
      doubleSided: material.doubleSided,
    });
  }
  const lights = buildEmissiveLightTable(emissive);
  const min: [number, number, number] = [Infinity, Infinity, Infinity];
  const max: [number, number, number] = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < p.length; i += 3) {
    for (let c = 0; c < 3; c++) {
      const v = p[i + c]!;
      if (v < min[c]!) min[c] = v;
      if (v > max[c]!) max[c] = v;
    }
  }
  return {
    source,
    triangleCount: source.triangleCount,
    nodeCount: bvh.nodeCount,
    bvhDepth: bvh.depth,
    sahCost: bvh.sahCost,
    buildTimeMs: bvh.buildTimeMs,
    triangleOrder: order,
    triangles: packWavefrontTriangles(p, order, { materialIds: source.materialIds, meshIndices: source.meshIndices }),
    attributes: packAttributes(source, order, areas, lights.pmfByTriangle),
    nodes: packWavefrontBvhNodes(bvh),
    lights,
    bounds: { min, max },
  };
}

/** Builds the mesh BVH (binned SAH on the CPU) and packs everything the tracing kernels read. */
export function createWavefrontMeshAcceleration(meshes: readonly (WavefrontMeshInput | NormalizedMesh)[]): WavefrontMeshAcceleration {
  const source = createWavefrontGpuMeshSource(meshes);
  return finish(source, buildBvh(source.positions));
}

/**
 * The same, with the BVH build split into time slices that yield to the event loop, so a large mesh
 * does not freeze a browser tab (see buildBvhAsync).
 */
export async function createWavefrontMeshAccelerationAsync(
  meshes: readonly (WavefrontMeshInput | NormalizedMesh)[],
  options: { sliceMs?: number; signal?: AbortSignal } = {},
): Promise<WavefrontMeshAcceleration> {
  const source = createWavefrontGpuMeshSource(meshes);
  return finish(source, await buildBvhAsync(source.positions, options));
}
