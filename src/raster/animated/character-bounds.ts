/**
 * Conservative world bounds of the posed character without skinning on the CPU: a linear-blend
 * skinned vertex sum_i w_i M_i p is a convex combination of the points M_i p, so it lies in the
 * union over joints i of M_i applied to the bind-space box of the vertices joint i influences.
 * Morph targets widen each box by the largest displacement the current weights can cause.
 */
import { mat4d, vec3d } from 'wgpu-matrix';
import type { AnimatedModel } from '../../animation/model/model-types.ts';

interface JointBox {
  skin: number;
  joint: number;
  min: number[];
  max: number[];
  /** Per morph target of the drawable: the largest |delta| component. */
  morphReach: number[];
  drawable: number;
}

interface RigidBox {
  drawable: number;
  node: number;
  min: number[];
  max: number[];
  morphReach: number[];
}

export interface CharacterBounds {
  /** World-space axis-aligned box: [min, max]. */
  at(root: ArrayLike<number>, world: Float64Array, jointMatrices: readonly ArrayLike<number>[], morphWeights: readonly ArrayLike<number>[]): { min: number[]; max: number[] };
}

export function createCharacterBounds(model: AnimatedModel): CharacterBounds {
  const joints = new Map<string, JointBox>();
  const rigid: RigidBox[] = [];
  model.drawables.forEach((d, di) => {
    for (const p of model.meshes[d.mesh]!.primitives) {
      const reach = p.targets.map((t) => Math.max(0, ...[t.positions].flatMap((a) => (a === null ? [0] : Array.from(a, Math.abs)))));
      if (d.skin < 0 || p.influences === 0) {
        const box: RigidBox = { drawable: di, node: d.node, min: [Infinity, Infinity, Infinity], max: [-Infinity, -Infinity, -Infinity], morphReach: reach };
        for (let v = 0; v < p.vertexCount; v++) for (let k = 0; k < 3; k++) {
          box.min[k] = Math.min(box.min[k]!, p.positions[3 * v + k]!);
          box.max[k] = Math.max(box.max[k]!, p.positions[3 * v + k]!);
        }
        rigid.push(box);
        continue;
      }
      for (let v = 0; v < p.vertexCount; v++) {
        for (let i = 0; i < p.influences; i++) {
          if (p.weights![p.influences * v + i]! === 0) continue;
          const j = p.joints![p.influences * v + i]!;
          const key = `${d.skin}:${j}:${di}`;
          let box = joints.get(key);
          if (box === undefined) {
            box = { skin: d.skin, joint: j, min: [Infinity, Infinity, Infinity], max: [-Infinity, -Infinity, -Infinity], morphReach: reach, drawable: di };
            joints.set(key, box);
          }
          for (let k = 0; k < 3; k++) {
            box.min[k] = Math.min(box.min[k]!, p.positions[3 * v + k]!);
            box.max[k] = Math.max(box.max[k]!, p.positions[3 * v + k]!);
          }
        }
      }
    }
  });
  const extend = (out: { min: number[]; max: number[] }, m: ArrayLike<number>, box: { min: number[]; max: number[]; morphReach: number[] }, weights: ArrayLike<number> | undefined): void => {
    let grow = 0;
    box.morphReach.forEach((r, t) => (grow += Math.abs(weights?.[t] ?? 0) * r));
    for (let c = 0; c < 8; c++) {
      const p = [0, 1, 2].map((k) => ((c >> k) & 1 ? box.max[k]! + grow : box.min[k]! - grow));
      const w = vec3d.transformMat4(p, m);
      for (let k = 0; k < 3; k++) {
        out.min[k] = Math.min(out.min[k]!, w[k]!);
        out.max[k] = Math.max(out.max[k]!, w[k]!);
      }
    }
  };
  return {
    at(root, world, jointMatrices, morphWeights) {
      const out = { min: [Infinity, Infinity, Infinity], max: [-Infinity, -Infinity, -Infinity] };
      for (const box of joints.values()) {
        const jm = jointMatrices[box.skin]!;
        extend(out, mat4d.multiply(root, Array.from({ length: 16 }, (_, i) => jm[16 * box.joint + i]!)), box, morphWeights[box.drawable]);
      }
      for (const box of rigid) extend(out, mat4d.multiply(root, world.subarray(16 * box.node, 16 * box.node + 16)), box, morphWeights[box.drawable]);
      return out;
    },
  };
}
