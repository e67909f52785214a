import type { ModelPrimitive } from '../model/model-types.ts';

export interface MorphedStreams {
  positions: Float64Array;
  normals: Float64Array | null;
  /** xyzw; w copied from the base tangent. */
  tangents: Float64Array | null;
}

/**
 * Applies morph targets (glTF 2.0 section 3.7.2.2): attribute = base + sum_i weight_i * delta_i,
 * for positions, normals and tangent xyz. Normals and tangents are left unnormalised here; the
 * skinning step normalises them after transforming.
 */
export function applyMorphTargets(primitive: Pick<ModelPrimitive, 'vertexCount' | 'positions' | 'normals' | 'tangents' | 'targets'>, weights: ArrayLike<number>): MorphedStreams {
  const positions = Float64Array.from(primitive.positions);
  const normals = primitive.normals === null ? null : Float64Array.from(primitive.normals);
  const tangents = primitive.tangents === null ? null : Float64Array.from(primitive.tangents);
  const n = primitive.vertexCount;
  primitive.targets.forEach((target, t) => {
    const w = weights[t] ?? 0;
    if (w === 0) return;
    if (target.positions !== null) for (let i = 0; i < 3 * n; i++) positions[i] += w * target.positions[i];
    if (target.normals !== null && normals !== null) for (let i = 0; i < 3 * n; i++) normals[i] += w * target.normals[i];
    if (target.tangents !== null && tangents !== null) {
      for (let v = 0; v < n; v++) for (let c = 0; c < 3; c++) tangents[4 * v + c] += w * target.tangents[3 * v + c];
    }
  });
  return { positions, normals, tangents };
}
