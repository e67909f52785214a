/**
 * One glTF primitive -> posed triangle-list vertex streams for the path tracer. The primitive is
 * read and validated by the one primitive reader (./primitive/read-primitive.ts, errors INVALID_GLTF
 * with JSON pointers); morph targets are then applied with the given weights (glTF 2.0 section
 * 3.7.2.2: base + sum of weight * target), then the node's skin when it has one (section 3.7.3), by
 * src/animation's reference code, the arithmetic the raster renderer poses with.
 */
import type { Primitive } from '@gltf-transform/core';
import { applyMorphTargets } from '../../animation/skinning/morph-targets.ts';
import { skinVertices } from '../../animation/skinning/skin-vertices.ts';
import { firstNonFinite } from '../accessors.ts';
import { failGltf } from './errors.ts';
import { readGltfPrimitive, type GltfPrimitive } from './primitive/read-primitive.ts';
import { checkSkinInfluences } from './primitive/skin-influences.ts';
import type { VertexStreams } from './vertex-streams.ts';

export interface PrimitiveGeometryOptions {
  /** JSON pointer of the primitive (`/meshes/2/primitives/0`). */
  at: string;
  /** Morph target weights (the node's, else the mesh's defaults). */
  weights: readonly number[];
  /** KHR_mesh_primitive_restart is in use: the largest index value restarts strips and fans. */
  primitiveRestart: boolean;
  /** Notes about data left out (the caller prefixes the primitive's pointer). */
  warn?: (message: string) => void;
  /**
   * The skin of the node drawing the primitive: its joint matrices (16 per joint, column-major,
   * world x inverse bind) and joint count. The vertices come out skinned into world space
   * (section 3.7.3.1: the skinned node's own transform does not apply).
   */
  skin?: { jointMatrices: Float64Array; jointCount: number };
}

function normalized(values: Float64Array | null, size: number): Float32Array | undefined {
  if (values === null) return undefined;
  const out = Float32Array.from(values);
  for (let i = 0; i < out.length; i += size) {
    const len = Math.hypot(out[i], out[i + 1], out[i + 2]);
    if (len > 0) for (let k = 0; k < 3; k++) out[i + k] /= len;
  }
  return out;
}

/**
 * Morph targets, then (with a skin) linear blend skinning, by src/animation's reference code (the
 * arithmetic the raster renderer's skinning shader mirrors). Normals and tangents come out unit length.
 */
function deform(read: GltfPrimitive, options: PrimitiveGeometryOptions): { positions: Float32Array; normals?: Float32Array; tangents?: Float32Array } {
  const morphed = applyMorphTargets(read, options.weights);
  const streams = options.skin === undefined ? morphed : skinVertices(read, morphed, options.skin.jointMatrices);
  const positions = Float32Array.from(streams.positions);
  const bad = firstNonFinite(positions);
  if (bad >= 0) failGltf(options.skin === undefined ? `${options.at}/targets` : `${options.at}/attributes/JOINTS_0`, `${options.skin === undefined ? 'morphed' : 'skinned'} POSITION element ${Math.floor(bad / 3)} is not finite`);
  const out: { positions: Float32Array; normals?: Float32Array; tangents?: Float32Array } = { positions };
  const normals = normalized(streams.normals, 3);
  const tangents = normalized(streams.tangents, 4);
  if (normals !== undefined) out.normals = normals;
  if (tangents !== undefined) out.tangents = tangents;
  return out;
}

/**
 * The primitive's triangles, or a reason it has none the renderer can draw (then the caller warns
 * and skips it).
 */
export function primitiveGeometry(primitive: Primitive, options: PrimitiveGeometryOptions): VertexStreams | { skip: string } {
  const { at, skin } = options;
  const read = readGltfPrimitive(primitive, {
    at,
    fault: failGltf,
    primitiveRestart: options.primitiveRestart,
    // Influences only where a skin poses them; morph targets only where a weight moves them.
    influences: skin !== undefined,
    readTarget: (t) => (options.weights[t] ?? 0) !== 0,
    warn: (message) => options.warn?.(message),
  });
  if ('skip' in read) return { skip: read.skip };
  if (skin !== undefined) checkSkinInfluences(read, at, skin.jointCount, failGltf);
  let positions = read.positions;
  let normals = read.normals ?? undefined;
  let tangents = read.tangents ?? undefined;
  if (options.weights.some((w) => w !== 0) || skin !== undefined) ({ positions, normals, tangents } = deform(read, options));
  const streams: VertexStreams = { positions, indices: read.indices };
  if (normals !== undefined) streams.normals = normals;
  if (tangents !== undefined) streams.tangents = tangents;
  if (read.uvs !== null) streams.uvs = read.uvs;
  if (read.uvs1 !== null) streams.uvs1 = read.uvs1;
  if (read.colors !== null) streams.colors = read.colors;
  return streams;
}
