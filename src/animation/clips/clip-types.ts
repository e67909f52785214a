/**
 * Keyframe animation data (glTF 2.0 section 3.11): a clip is a set of channels, each driving one
 * property of one node through a sampler (keyframe times in seconds, output values, interpolation).
 */

export type AnimationInterpolation = 'STEP' | 'LINEAR' | 'CUBICSPLINE';
export type AnimationChannelPath = 'translation' | 'rotation' | 'scale' | 'weights';

export interface AnimationSamplerData {
  readonly interpolation: AnimationInterpolation;
  /** Keyframe times in seconds: finite, >= 0, strictly increasing. */
  readonly input: Float64Array;
  /**
   * Output values, `components` per element. CUBICSPLINE stores three elements per keyframe:
   * in-tangent, value, out-tangent (glTF 2.0 Appendix C).
   */
  readonly output: Float64Array;
  /** 3 (translation, scale), 4 (rotation) or the morph target count (weights). */
  readonly components: number;
}

export interface AnimationChannelData {
  /** Target node index in the model the clip is bound to. */
  readonly node: number;
  /** Target node name (how clips from separate files are bound to a model). */
  readonly nodeName: string;
  readonly path: AnimationChannelPath;
  readonly sampler: AnimationSamplerData;
  /** Where the channel came from, for errors: e.g. `clipAssets[1].animations[0].channels[3]`. */
  readonly field: string;
}

export interface AnimationClip {
  /** Unique id within a clip library (defaults to the glTF animation name). */
  readonly id: string;
  readonly name: string;
  /** Largest keyframe time over all samplers, in seconds (the clip loops over [0, duration]). */
  readonly durationS: number;
  readonly channels: readonly AnimationChannelData[];
  readonly field: string;
}
