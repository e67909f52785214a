import { mat4d } from 'wgpu-matrix';
import { composeTrs } from '../../math/mat4.ts';
import type { AnimatedModel } from '../model/model-types.ts';
import type { Pose } from './pose.ts';

/**
 * World (model-space) matrix of every node for a pose: world(n) = world(parent) * local(n),
 * evaluated parents first. Returns 16 column-major values per node, in node order.
 */
export function computeWorldMatrices(model: Pick<AnimatedModel, 'nodes' | 'nodeOrder'>, pose: Pose, out?: Float64Array): Float64Array {
  const world = out ?? new Float64Array(16 * model.nodes.length);
  const local = new Float64Array(16);
  for (const n of model.nodeOrder) {
    const target = world.subarray(16 * n, 16 * n + 16);
    const parent = model.nodes[n].parent;
    if (parent < 0) {
      composeTrs(pose.translations, 3 * n, pose.rotations, 4 * n, pose.scales, 3 * n, world, 16 * n);
    } else {
      composeTrs(pose.translations, 3 * n, pose.rotations, 4 * n, pose.scales, 3 * n, local, 0);
      mat4d.multiply(world.subarray(16 * parent, 16 * parent + 16), local, target);
    }
  }
  return world;
}

/**
 * Joint matrices of a skin: jointMatrix(j) = world(joint j) * inverseBindMatrix(j). Per glTF 2.0
 * section 3.7.3.1 only the joint transforms place a skinned mesh; the transform of the node that
 * carries the mesh is ignored, so skinned vertices come out in model space.
 */
export function computeJointMatrices(model: Pick<AnimatedModel, 'skins'>, skinIndex: number, world: Float64Array, out?: Float64Array): Float64Array {
  const skin = model.skins[skinIndex];
  const joints = out ?? new Float64Array(16 * skin.joints.length);
  for (let j = 0; j < skin.joints.length; j++) {
    const n = skin.joints[j];
    mat4d.multiply(world.subarray(16 * n, 16 * n + 16), skin.inverseBindMatrices.subarray(16 * j, 16 * j + 16), joints.subarray(16 * j, 16 * j + 16));
  }
  return joints;
}
