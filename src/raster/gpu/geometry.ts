/**
 * Vertex and index buffers of the drawn meshes: one float stream per attribute (positions,
 * normals, tangents, uv0, uv1, colours), the layout the forward and shadow pipelines read. Streams
 * a mesh lacks are bound as zero-filled buffers and flagged in the draw uniform, so the shader
 * derives what it needs instead (facet normals, uv-derivative tangents).
 */
import { BufferUsage } from '../../gpu/webgpu-constants.ts';
import type { NormalizedMesh } from '../../scene/mesh.ts';
import { rasterConstants } from './raster-layout.ts';

export interface GpuMeshStreams {
  /** Vertex buffers in vertexBufferLayouts order (positions may be replaced by skinned output). */
  readonly buffers: { buffer: GPUBuffer; offset: number }[];
  readonly indexBuffer: GPUBuffer;
  readonly indexCount: number;
  readonly vertexCount: number;
  readonly flags: number;
  /** Object-space bounds: centre and radius. */
  readonly center: [number, number, number];
  readonly radius: number;
  readonly bytes: number;
  destroy(): void;
}

function upload(device: GPUDevice, data: ArrayBufferView, usage: number, label: string): GPUBuffer {
  const size = Math.max(16, Math.ceil(data.byteLength / 4) * 4);
  const buffer = device.createBuffer({ label, size, usage: usage | BufferUsage.COPY_DST, mappedAtCreation: true });
  new Uint8Array(buffer.getMappedRange()).set(new Uint8Array(data.buffer, data.byteOffset, data.byteLength));
  buffer.unmap();
  return buffer;
}

export function meshBounds(positions: Float32Array): { center: [number, number, number]; radius: number } {
  const min = [Infinity, Infinity, Infinity];
  const max = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < positions.length; i += 3) {
    for (let c = 0; c < 3; c++) {
      min[c] = Math.min(min[c]!, positions[i + c]!);
      max[c] = Math.max(max[c]!, positions[i + c]!);
    }
  }
  if (positions.length === 0) return { center: [0, 0, 0], radius: 0 };
  const center: [number, number, number] = [0.5 * (min[0]! + max[0]!), 0.5 * (min[1]! + max[1]!), 0.5 * (min[2]! + max[2]!)];
  return { center, radius: 0.5 * Math.hypot(max[0]! - min[0]!, max[1]! - min[1]!, max[2]! - min[2]!) };
}

export function uploadMeshStreams(device: GPUDevice, mesh: NormalizedMesh, label: string): GpuMeshStreams {
  const n = mesh.vertexCount;
  const V = BufferUsage.VERTEX;
  let flags = 0;
  const stream = (data: Float32Array | null, components: number, flag: number, fill = 0): GPUBuffer => {
    if (data !== null) flags |= flag;
    return upload(device, data ?? new Float32Array(components * n).fill(fill), V, `${label} stream`);
  };
  const buffers = [
    upload(device, mesh.positions, V, `${label} positions`),
    stream(mesh.normals, 3, rasterConstants.DRAW_HAS_NORMALS),
    stream(mesh.tangents, 4, rasterConstants.DRAW_HAS_TANGENTS),
    stream(mesh.uvs, 2, rasterConstants.DRAW_HAS_UV0),
    stream(mesh.uvs1, 2, rasterConstants.DRAW_HAS_UV1),
    stream(mesh.colors, 4, rasterConstants.DRAW_HAS_COLORS, 1),
  ];
  const indexBuffer = upload(device, mesh.indices, BufferUsage.INDEX, `${label} indices`);
  const bounds = meshBounds(mesh.positions);
  const bytes = buffers.reduce((s, b) => s + b.size, 0) + indexBuffer.size;
  return {
    buffers: buffers.map((buffer) => ({ buffer, offset: 0 })),
    indexBuffer,
    indexCount: mesh.indices.length,
    vertexCount: n,
    flags,
    ...bounds,
    bytes,
    destroy() {
      for (const b of buffers) b.destroy();
      indexBuffer.destroy();
    },
  };
}
