import type { AnimationClip } from '../clips/clip-types.ts';
import type { AnimatedModel } from '../model/model-types.ts';
import { blendPoses, type PoseLayer } from './blend-poses.ts';
import { evaluateClipPose } from './evaluate-clip.ts';
import { createRestPose, type Pose } from './pose.ts';
import { removeHorizontalRootMotion, type RootMotionNode } from './root-motion.ts';

/** One clip playing at one instant, with its cross-fade weight and root-motion policy. */
export interface ClipLayer {
  readonly clip: AnimationClip;
  /** Time inside the clip (already looped), ms. */
  readonly clipTimeMs: number;
  readonly weight: number;
  /** 'in-place' removes the root's horizontal travel (the route moves the character instead). */
  readonly rootMotion: 'authored' | 'in-place';
  readonly root: RootMotionNode | null;
}

/** Evaluates each layer's clip pose (made in-place when asked) and cross-fades them. */
export function evaluateLayeredPose(model: Pick<AnimatedModel, 'nodes'>, layers: readonly ClipLayer[], out?: Pose): Pose {
  const rest = createRestPose(model);
  const poses: PoseLayer[] = layers.map((layer) => {
    const timeS = layer.clipTimeMs / 1000;
    const pose = evaluateClipPose(model, layer.clip, timeS, createRestPose(model), rest);
    if (layer.rootMotion === 'in-place') removeHorizontalRootMotion(pose, layer.clip, layer.root, timeS);
    return { pose, weight: layer.weight };
  });
  if (poses.length === 0) return out === undefined ? rest : blendPoses([{ pose: rest, weight: 1 }], out);
  return blendPoses(poses, out ?? createRestPose(model));
}
