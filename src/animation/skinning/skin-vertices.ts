import type { ModelPrimitive } from '../model/model-types.ts';
import type { MorphedStreams } from './morph-targets.ts';

export interface SkinnedStreams {
  positions: Float64Array;
  normals: Float64Array | null;
  tangents: Float64Array | null;
}

/**
 * CPU reference linear blend skinning (glTF 2.0 section 3.7.3.3): per vertex the skin matrix
 * M = sum_i w_i * jointMatrix[j_i] over 4 (JOINTS_0) or 8 (JOINTS_0 + JOINTS_1) influences, with
 * weights already normalised at load. Positions: M p. Normals: the inverse transpose of M's upper
 * 3x3, computed as its cofactor matrix divided by the determinant (exact for any non-singular
 * blend, including non-uniform scale), then normalised. Tangents: M's 3x3 times xyz, normalised,
 * w (bitangent sign) kept. A singular blend (zero-scaled joints collapse the vertex) keeps the
 * cofactor direction, which is the limit of the inverse transpose.
 */
export function skinVertices(primitive: Pick<ModelPrimitive, 'vertexCount' | 'influences' | 'joints' | 'weights'>, streams: MorphedStreams, jointMatrices: Float64Array): SkinnedStreams {
  const n = primitive.vertexCount;
  const influences = primitive.influences;
  const joints = primitive.joints;
  const weights = primitive.weights;
  if (influences === 0 || joints === null || weights === null) throw new RangeError('skinVertices needs a primitive with joint influences');
  const positions = new Float64Array(3 * n);
  const normals = streams.normals === null ? null : new Float64Array(3 * n);
  const tangents = streams.tangents === null ? null : new Float64Array(4 * n);
  const m = new Float64Array(12);
  for (let v = 0; v < n; v++) {
    m.fill(0);
    for (let i = 0; i < influences; i++) {
      const w = weights[influences * v + i];
      if (w === 0) continue;
      const o = 16 * joints[influences * v + i];
      // Affine joint matrices: accumulate the three upper rows' 12 entries (columns 0..3, rows 0..2).
      for (let c = 0; c < 4; c++) for (let r = 0; r < 3; r++) m[3 * c + r] += w * jointMatrices[o + 4 * c + r];
    }
    const px = streams.positions[3 * v], py = streams.positions[3 * v + 1], pz = streams.positions[3 * v + 2];
    for (let r = 0; r < 3; r++) positions[3 * v + r] = m[r] * px + m[3 + r] * py + m[6 + r] * pz + m[9 + r];
    if (normals !== null && streams.normals !== null) {
      const nx = streams.normals[3 * v], ny = streams.normals[3 * v + 1], nz = streams.normals[3 * v + 2];
      // Cofactors of A (A[r][c] = m[3c + r]); inverse transpose = cofactor / det.
      const a00 = m[0], a01 = m[3], a02 = m[6], a10 = m[1], a11 = m[4], a12 = m[7], a20 = m[2], a21 = m[5], a22 = m[8];
      const c00 = a11 * a22 - a12 * a21, c01 = a12 * a20 - a10 * a22, c02 = a10 * a21 - a11 * a20;
      const c10 = a02 * a21 - a01 * a22, c11 = a00 * a22 - a02 * a20, c12 = a01 * a20 - a00 * a21;
      const c20 = a01 * a12 - a02 * a11, c21 = a02 * a10 - a00 * a12, c22 = a00 * a11 - a01 * a10;
      const det = a00 * c00 + a01 * c01 + a02 * c02;
      const sign = det < 0 ? -1 : 1;
      let x = sign * (c00 * nx + c01 * ny + c02 * nz);
      let y = sign * (c10 * nx + c11 * ny + c12 * nz);
      let z = sign * (c20 * nx + c21 * ny + c22 * nz);
      const length = Math.hypot(x, y, z);
      if (length > 0) { x /= length; y /= length; z /= length; }
      normals[3 * v] = x; normals[3 * v + 1] = y; normals[3 * v + 2] = z;
    }
    if (tangents !== null && streams.tangents !== null) {
      const tx = streams.tangents[4 * v], ty = streams.tangents[4 * v + 1], tz = streams.tangents[4 * v + 2];
      let x = m[0] * tx + m[3] * ty + m[6] * tz;
      let y = m[1] * tx + m[4] * ty + m[7] * tz;
      let z = m[2] * tx + m[5] * ty + m[8] * tz;
      const length = Math.hypot(x, y, z);
      if (length > 0) { x /= length; y /= length; z /= length; }
      tangents[4 * v] = x; tangents[4 * v + 1] = y; tangents[4 * v + 2] = z; tangents[4 * v + 3] = streams.tangents[4 * v + 3];
    }
  }
  return { positions, normals, tangents };
}
