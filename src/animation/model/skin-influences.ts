import type { Primitive } from '@gltf-transform/core';
import { fail } from '../../errors/validate.ts';
import { readFloatAccessor, readIndexAccessor } from '../../io/accessors.ts';

export interface SkinInfluences {
  influences: 0 | 4 | 8;
  joints: Uint16Array | null;
  weights: Float32Array | null;
}

/**
 * Reads JOINTS_0/WEIGHTS_0 and, when present, JOINTS_1/WEIGHTS_1 (8 influences per vertex).
 * glTF 2.0 section 3.7.3.3: weights MUST be non-negative and sum to 1; exporters quantise them, so
 * every vertex is renormalised here by its weight sum (a sum of 0 cannot be normalised and is an
 * error naming the vertex).
 */
export function readSkinInfluences(primitive: Primitive, field: string, vertexCount: number): SkinInfluences {
  const sets: { joints: Uint32Array; weights: Float64Array }[] = [];
  for (let set = 0; set < 2; set++) {
    const jointsAccessor = primitive.getAttribute(`JOINTS_${set}`);
    const weightsAccessor = primitive.getAttribute(`WEIGHTS_${set}`);
    if (jointsAccessor === null && weightsAccessor === null) break;
    if (jointsAccessor === null || weightsAccessor === null) {
      const missing = jointsAccessor === null ? `JOINTS_${set}` : `WEIGHTS_${set}`;
      fail('INVALID_MODEL', `${field}.attributes.${missing}`, `JOINTS_${set} and WEIGHTS_${set} must come together`);
    }
    const jointsField = `${field}.attributes.JOINTS_${set}`;
    const weightsField = `${field}.attributes.WEIGHTS_${set}`;
    const joints = readIndexAccessor(jointsAccessor, jointsField, 'INVALID_MODEL', ['VEC4']);
    const weights = readFloatAccessor(weightsAccessor, weightsField, 'INVALID_MODEL', ['VEC4']);
    if (joints.length !== 4 * vertexCount) fail('INVALID_MODEL', jointsField, `has ${joints.length / 4} elements but POSITION has ${vertexCount}`);
    if (weights.length !== 4 * vertexCount) fail('INVALID_MODEL', weightsField, `has ${weights.length / 4} elements but POSITION has ${vertexCount}`);
    sets.push({ joints, weights });
  }
  if (sets.length === 0) return { influences: 0, joints: null, weights: null };
  const influences = (4 * sets.length) as 4 | 8;
  const joints = new Uint16Array(influences * vertexCount);
  const weights = new Float32Array(influences * vertexCount);
  for (let v = 0; v < vertexCount; v++) {
    let sum = 0;
    for (let s = 0; s < sets.length; s++) {
      for (let k = 0; k < 4; k++) {
        const w = sets[s].weights[4 * v + k];
        if (w < 0) fail('INVALID_MODEL', `${field}.attributes.WEIGHTS_${s}[${v}]`, `joint weight ${w} is negative`);
        if (sets[s].joints[4 * v + k] > 0xffff) fail('INVALID_MODEL', `${field}.attributes.JOINTS_${s}[${v}]`, 'joint index exceeds 65535');
        sum += w;
      }
    }
    if (!(sum > 0)) fail('INVALID_MODEL', `${field}.attributes.WEIGHTS_0[${v}]`, 'joint weights of this vertex sum to 0');
    for (let s = 0; s < sets.length; s++) {
      for (let k = 0; k < 4; k++) {
        joints[influences * v + 4 * s + k] = sets[s].joints[4 * v + k];
        weights[influences * v + 4 * s + k] = sets[s].weights[4 * v + k] / sum;
      }
    }
  }
  return { influences, joints, weights };
}

/**
 * Checks a skinned primitive's joint indices against its skin's joint count: an index out of range
 * with a positive weight is an error naming the vertex (`field` is the primitive's, errors read
 * `field.attributes.JOINTS_n[v]`); unused slots (weight 0) often hold padding indices and are
 * pointed at joint 0 in place, so no consumer (a GPU palette lookup) reads past the palette.
 */
export function checkJointRange(influences: SkinInfluences, field: string, jointCount: number): void {
  const { joints, weights, influences: n } = influences;
  if (joints === null || weights === null) return;
  for (let i = 0; i < joints.length; i++) {
    if (joints[i] < jointCount) continue;
    if (weights[i] > 0) {
      fail('INVALID_MODEL', `${field}.attributes.JOINTS_${i % n >= 4 ? 1 : 0}[${Math.floor(i / n)}]`, `joint index ${joints[i]} is out of range for a skin of ${jointCount} joints`);
    }
    joints[i] = 0;
  }
}
