import type { AnimatedModel } from '../model/model-types.ts';

/**
 * Local transforms of every node at one instant: translation (3 per node), rotation quaternion
 * (4 per node, x y z w) and scale (3 per node), plus the morph weights of every node that draws a
 * mesh with morph targets (an empty array otherwise).
 */
export interface Pose {
  readonly translations: Float64Array;
  readonly rotations: Float64Array;
  readonly scales: Float64Array;
  readonly weights: Float64Array[];
}

/** The model's rest pose: every node at its authored TRS, morph weights at their defaults. */
export function createRestPose(model: Pick<AnimatedModel, 'nodes'>): Pose {
  const n = model.nodes.length;
  const pose: Pose = {
    translations: new Float64Array(3 * n),
    rotations: new Float64Array(4 * n),
    scales: new Float64Array(3 * n),
    weights: model.nodes.map((node) => Float64Array.from(node.weights)),
  };
  model.nodes.forEach((node, i) => {
    pose.translations.set(node.translation, 3 * i);
    pose.rotations.set(node.rotation, 4 * i);
    pose.scales.set(node.scale, 3 * i);
  });
  return pose;
}

export function copyPose(source: Pose, target: Pose): Pose {
  target.translations.set(source.translations);
  target.rotations.set(source.rotations);
  target.scales.set(source.scales);
  source.weights.forEach((w, i) => target.weights[i].set(w));
  return target;
}
