import type { AnimationClip } from '../clips/clip-types.ts';
import type { AnimatedModel } from '../model/model-types.ts';
import { sampleAnimationSampler } from '../sampling/sample-sampler.ts';
import { copyPose, createRestPose, type Pose } from './pose.ts';

/**
 * The pose of a clip at `timeS` seconds: the rest pose with every channel's sampled value written
 * over its node's property (glTF 2.0 section 3.11: channels replace the targeted property).
 * `timeS` is used as given; looping is the caller's choice (see `loopClipTime`).
 */
export function evaluateClipPose(model: Pick<AnimatedModel, 'nodes'>, clip: AnimationClip, timeS: number, out?: Pose, rest?: Pose): Pose {
  const pose = out ?? createRestPose(model);
  if (out !== undefined) copyPose(rest ?? createRestPose(model), pose);
  for (const channel of clip.channels) {
    const n = channel.node;
    switch (channel.path) {
      case 'translation':
        sampleAnimationSampler(channel.sampler, timeS, false, pose.translations, 3 * n);
        break;
      case 'rotation':
        sampleAnimationSampler(channel.sampler, timeS, true, pose.rotations, 4 * n);
        break;
      case 'scale':
        sampleAnimationSampler(channel.sampler, timeS, false, pose.scales, 3 * n);
        break;
      case 'weights':
        sampleAnimationSampler(channel.sampler, timeS, false, pose.weights[n], 0);
        break;
    }
  }
  return pose;
}

/** Wraps a time in milliseconds into a clip of `durationS` seconds: [0, duration). */
export function loopClipTimeMs(timeMs: number, durationS: number): number {
  const durationMs = durationS * 1000;
  if (!(durationMs > 0)) return 0;
  const wrapped = timeMs % durationMs;
  return wrapped < 0 ? wrapped + durationMs : wrapped;
}
