/**
 * A primitive's joint influences (glTF 2.0 section 3.7.3.3): JOINTS_0/WEIGHTS_0 and, when present,
 * JOINTS_1/WEIGHTS_1 (8 influences per vertex). Weights MUST be non-negative and sum to 1;
 * exporters quantise them, so every vertex is renormalised by its weight sum (a sum of 0 cannot be
 * normalised and is a fault naming the vertex). Faults name JSON pointers below the primitive's,
 * with the vertex as the last segment where one vertex is at fault (`.../attributes/WEIGHTS_0/12`).
 */
import type { Accessor, Primitive } from '@gltf-transform/core';
import { accessorToFloat32, firstNonFinite } from '../../accessors.ts';
import type { PrimitiveFault } from './primitive-fault.ts';

export interface SkinInfluences {
  /** Joint influences per vertex: 0 (not skinned), 4 (JOINTS_0) or 8 (JOINTS_0 + JOINTS_1). */
  readonly influences: 0 | 4 | 8;
  /** `influences` joint indices per vertex, into the skin's `joints`. */
  readonly joints: Uint16Array | null;
  /** `influences` weights per vertex, normalised to sum 1 (glTF 2.0 section 3.7.3.3). */
  readonly weights: Float32Array | null;
}

/** A JOINTS_n accessor's indices: four non-negative integers per vertex, each at most 65535. */
function readJoints(accessor: Accessor, at: string, vertexCount: number, fault: PrimitiveFault): Uint32Array {
  if (accessor.getElementSize() !== 4) fault(at, `joint indices must have 4 components per element, the accessor has ${accessor.getElementSize()}`);
  if (accessor.getNormalized()) fault(at, 'joint indices must be integers, the accessor is normalized');
  if (accessor.getCount() !== vertexCount) fault(at, `${accessor.getCount()} elements, the primitive's POSITION has ${vertexCount}`);
  const source = accessor.getArray();
  const out = new Uint32Array(4 * vertexCount);
  if (source === null) return out;
  for (let i = 0; i < out.length; i++) {
    const j = Number(source[i]);
    if (!Number.isInteger(j) || j < 0) fault(`${at}/${Math.floor(i / 4)}`, `expected a non-negative integer joint index, got ${j}`);
    if (j > 0xffff) fault(`${at}/${Math.floor(i / 4)}`, `joint index ${j} exceeds 65535`);
    out[i] = j;
  }
  return out;
}

/** A WEIGHTS_n accessor's weights: four finite, non-negative numbers per vertex. */
function readWeights(accessor: Accessor, at: string, vertexCount: number, fault: PrimitiveFault): Float32Array {
  if (accessor.getElementSize() !== 4) fault(at, `joint weights must have 4 components per element, the accessor has ${accessor.getElementSize()}`);
  if (accessor.getCount() !== vertexCount) fault(at, `${accessor.getCount()} elements, the primitive's POSITION has ${vertexCount}`);
  const weights = accessorToFloat32(accessor);
  const bad = firstNonFinite(weights);
  if (bad >= 0) fault(`${at}/${Math.floor(bad / 4)}`, `joint weight ${weights[bad]} is not finite`);
  for (let i = 0; i < weights.length; i++) {
    if (weights[i] < 0) fault(`${at}/${Math.floor(i / 4)}`, `joint weight ${weights[i]} is negative`);
  }
  return weights;
}

/** Reads and normalises the primitive's influences; `at` is the primitive's pointer. */
export function readSkinInfluences(primitive: Primitive, at: string, vertexCount: number, fault: PrimitiveFault): SkinInfluences {
  const sets: { joints: Uint32Array; weights: Float32Array }[] = [];
  for (let set = 0; set < 2; set++) {
    const jointsAccessor = primitive.getAttribute(`JOINTS_${set}`);
    const weightsAccessor = primitive.getAttribute(`WEIGHTS_${set}`);
    if (jointsAccessor === null && weightsAccessor === null) break;
    if (jointsAccessor === null || weightsAccessor === null) {
      const missing = jointsAccessor === null ? `JOINTS_${set}` : `WEIGHTS_${set}`;
      fault(`${at}/attributes/${missing}`, `JOINTS_${set} and WEIGHTS_${set} must come together`);
    }
    sets.push({
      joints: readJoints(jointsAccessor, `${at}/attributes/JOINTS_${set}`, vertexCount, fault),
      weights: readWeights(weightsAccessor, `${at}/attributes/WEIGHTS_${set}`, vertexCount, fault),
    });
  }
  if (sets.length === 0) return { influences: 0, joints: null, weights: null };
  const influences = (4 * sets.length) as 4 | 8;
  const joints = new Uint16Array(influences * vertexCount);
  const weights = new Float32Array(influences * vertexCount);
  for (let v = 0; v < vertexCount; v++) {
    let sum = 0;
    for (const set of sets) for (let k = 0; k < 4; k++) sum += set.weights[4 * v + k];
    if (!(sum > 0)) fault(`${at}/attributes/WEIGHTS_0/${v}`, 'joint weights of this vertex sum to 0');
    sets.forEach((set, s) => {
      for (let k = 0; k < 4; k++) {
        joints[influences * v + 4 * s + k] = set.joints[4 * v + k];
        weights[influences * v + 4 * s + k] = set.weights[4 * v + k] / sum;
      }
    });
  }
  return { influences, joints, weights };
}

/**
 * Checks the influences of a primitive drawn with a skin of `jointCount` joints (section 3.7.3):
 * it must have influences, and a joint index out of range with a positive weight is a fault naming
 * the vertex. Unused slots (weight 0) often hold padding indices; they are pointed at joint 0 in
 * place, so no consumer (a GPU palette lookup) reads past the palette.
 */
export function checkSkinInfluences(influences: SkinInfluences, at: string, jointCount: number, fault: PrimitiveFault): void {
  const { joints, weights, influences: n } = influences;
  if (joints === null || weights === null) return fault(`${at}/attributes/JOINTS_0`, 'the mesh is drawn by a node with a skin; a skinned mesh needs JOINTS_0 and WEIGHTS_0');
  for (let i = 0; i < joints.length; i++) {
    if (joints[i] < jointCount) continue;
    if (weights[i] > 0) fault(`${at}/attributes/JOINTS_${i % n >= 4 ? 1 : 0}/${Math.floor(i / n)}`, `joint index ${joints[i]} is out of range for a skin of ${jointCount} joints`);
    joints[i] = 0;
  }
}
