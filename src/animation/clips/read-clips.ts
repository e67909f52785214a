import type { AnimationSampler, Document, Node } from '@gltf-transform/core';
import { fail } from '../../errors/validate.ts';
import { readFloatAccessor } from '../../io/accessors.ts';
import type { AnimationChannelData, AnimationChannelPath, AnimationClip, AnimationInterpolation, AnimationSamplerData } from './clip-types.ts';

const PATH_COMPONENTS: Record<string, number> = { translation: 3, rotation: 4, scale: 3 };
const PATH_TYPES: Record<string, string> = { translation: 'VEC3', rotation: 'VEC4', scale: 'VEC3', weights: 'SCALAR' };
const INTERPOLATIONS: readonly string[] = ['STEP', 'LINEAR', 'CUBICSPLINE'];

/**
 * Validates and reads one sampler (glTF 2.0 section 3.11 and the animation.sampler schema): times
 * finite, `time[0] >= 0`, strictly increasing; output element type matching the path; output count
 * equal to the key count (three times for CUBICSPLINE, which needs at least two keys).
 */
function readSampler(sampler: AnimationSampler, path: AnimationChannelPath, field: string): AnimationSamplerData {
  // An absent interpolation means LINEAR (animation.sampler schema default).
  const interpolation = sampler.getInterpolation() ?? 'LINEAR';
  if (!INTERPOLATIONS.includes(interpolation)) fail('INVALID_ANIMATION', `${field}.interpolation`, `unknown interpolation ${JSON.stringify(interpolation)}`);
  const inputAccessor = sampler.getInput();
  if (inputAccessor === null) fail('INVALID_ANIMATION', `${field}.input`, 'sampler has no input (keyframe times)');
  const outputAccessor = sampler.getOutput();
  if (outputAccessor === null) fail('INVALID_ANIMATION', `${field}.output`, 'sampler has no output (keyframe values)');
  const input = readFloatAccessor(inputAccessor, `${field}.input`, 'INVALID_ANIMATION', ['SCALAR']);
  if (input.length === 0) fail('INVALID_ANIMATION', `${field}.input`, 'sampler has no keyframes');
  if (input[0] < 0) fail('INVALID_ANIMATION', `${field}.input[0]`, `keyframe time ${input[0]} is negative`);
  for (let k = 1; k < input.length; k++) {
    if (!(input[k] > input[k - 1])) {
      fail('INVALID_ANIMATION', `${field}.input[${k}]`, `keyframe times must strictly increase (${input[k - 1]} then ${input[k]})`);
    }
  }
  const cubic = interpolation === 'CUBICSPLINE';
  if (cubic && input.length < 2) fail('INVALID_ANIMATION', `${field}.input`, 'CUBICSPLINE needs at least two keyframes');
  const output = readFloatAccessor(outputAccessor, `${field}.output`, 'INVALID_ANIMATION', [PATH_TYPES[path]]);
  const elementsPerKey = cubic ? 3 : 1;
  const outputCount = outputAccessor.getCount();
  let components: number;
  if (path === 'weights') {
    // Scalar outputs, one per morph target per key (section 3.11: "weights" outputs are N * targetCount).
    if (outputCount % (input.length * elementsPerKey) !== 0 || outputCount === 0) {
      fail('INVALID_ANIMATION', `${field}.output`, `${outputCount} weights do not divide into ${input.length} keyframes${cubic ? ' x 3' : ''}`);
    }
    components = outputCount / (input.length * elementsPerKey);
  } else {
    components = PATH_COMPONENTS[path];
    if (outputCount !== input.length * elementsPerKey) {
      fail('INVALID_ANIMATION', `${field}.output`, `has ${outputCount} elements, expected ${input.length * elementsPerKey} for ${input.length} keyframes (${interpolation})`);
    }
  }
  if (path === 'rotation') normaliseRotationKeys(output, input.length, cubic, `${field}.output`);
  return { interpolation: interpolation as AnimationInterpolation, input, output, components };
}

/** Keyframe rotations must be unit quaternions; quantised ones are renormalised, zero ones rejected. */
function normaliseRotationKeys(output: Float64Array, keys: number, cubic: boolean, field: string): void {
  for (let k = 0; k < keys; k++) {
    const element = cubic ? 3 * k + 1 : k;
    const o = 4 * element;
    const length = Math.hypot(output[o], output[o + 1], output[o + 2], output[o + 3]);
    if (length < 1e-6) fail('INVALID_ANIMATION', `${field}[${element}]`, 'rotation keyframe is a zero quaternion');
    if (!cubic) for (let c = 0; c < 4; c++) output[o + c] /= length;
  }
}

/**
 * Reads every animation of a document as clips whose channels target that document's nodes
 * (`indexOf`). Field paths follow the glTF JSON (`animations[a].channels[c].target.node`).
 */
export function readAnimationClips(document: Document, indexOf: Map<Node, number>, field: string): AnimationClip[] {
  const ids = new Set<string>();
  return document.getRoot().listAnimations().map((animation, a) => {
    const animationField = `${field}animations[${a}]`;
    const samplers = animation.listSamplers();
    const cache = new Map<string, AnimationSamplerData>();
    const channels: AnimationChannelData[] = animation.listChannels().map((channel, c) => {
      const channelField = `${animationField}.channels[${c}]`;
      const target = channel.getTargetNode();
      const nodeIndex = target === null ? undefined : indexOf.get(target);
      if (target === null || nodeIndex === undefined) fail('INVALID_ANIMATION', `${channelField}.target.node`, 'channel targets a node that does not exist');
      const path = channel.getTargetPath();
      if (path !== 'translation' && path !== 'rotation' && path !== 'scale' && path !== 'weights') {
        fail('INVALID_ANIMATION', `${channelField}.target.path`, `unsupported target path ${JSON.stringify(path)}`);
      }
      const sampler = channel.getSampler();
      if (sampler === null) fail('INVALID_ANIMATION', `${channelField}.sampler`, 'channel has no sampler');
      const s = samplers.indexOf(sampler);
      const samplerField = `${animationField}.samplers[${s < 0 ? c : s}]`;
      const key = `${s}:${path}`;
      const data = cache.get(key) ?? readSampler(sampler, path, samplerField);
      cache.set(key, data);
      return { node: nodeIndex, nodeName: target.getName(), path, sampler: data, field: channelField };
    });
    if (channels.length === 0) fail('INVALID_ANIMATION', `${animationField}.channels`, 'animation has no channels');
    let durationS = 0;
    for (const channel of channels) durationS = Math.max(durationS, channel.sampler.input[channel.sampler.input.length - 1]);
    const name = animation.getName();
    let id = name === '' ? `animation-${a}` : name;
    for (let n = 2; ids.has(id); n++) id = `${name === '' ? `animation-${a}` : name}-${n}`;
    ids.add(id);
    return { id, name, durationS, channels, field: animationField };
  });
}
