import { mat3d, mat4d } from 'wgpu-matrix';
import { fail } from '../../errors/validate.ts';
import type { AnimationClip, AnimationSamplerData } from '../clips/clip-types.ts';
import type { AnimatedModel, Vec3 } from '../model/model-types.ts';
import { sampleAnimationSampler } from '../sampling/sample-sampler.ts';
import { createRestPose, type Pose } from './pose.ts';
import { computeWorldMatrices } from './world-matrices.ts';

/**
 * Root motion: the horizontal travel a clip authors on its root joint (Mixamo's "Hips", for
 * example). Travel is measured and removed in model space (+Y up, glTF 2.0 section 3.4), so a
 * scaled or rotated parent (Mixamo's 0.01-scaled "Armature") is accounted for.
 */
export interface RootMotionNode {
  readonly node: number;
  /** Upper 3x3 of the parent's rest world matrix (column-major, 12 floats as wgpu-matrix mat3) and its inverse. */
  readonly parentLinear: Float64Array;
  readonly parentLinearInverse: Float64Array;
}

/**
 * The root-motion node: `name` when given (an error naming `field` when the model lacks it), else
 * the top-most joint of the first skin (a joint whose parent is not a joint of that skin).
 */
export function resolveRootMotionNode(model: Pick<AnimatedModel, 'nodes' | 'nodeOrder' | 'skins'>, name?: string, field = 'rootNode'): RootMotionNode | null {
  let node = -1;
  if (name !== undefined) {
    node = model.nodes.findIndex((n) => n.name === name);
    if (node < 0) fail('INVALID_OPTION', field, `the model has no node named ${JSON.stringify(name)}`);
  } else if (model.skins.length > 0) {
    const joints = new Set(model.skins[0].joints);
    node = [...model.skins[0].joints].find((j) => !joints.has(model.nodes[j].parent)) ?? -1;
  }
  if (node < 0) return null;
  const world = computeWorldMatrices(model, createRestPose(model));
  const parent = model.nodes[node].parent;
  const parentLinear = mat3d.fromMat4(parent < 0 ? mat4d.identity() : world.subarray(16 * parent, 16 * parent + 16));
  const parentLinearInverse = mat3d.inverse(parentLinear);
  return { node, parentLinear, parentLinearInverse };
}

function rootTranslationSampler(clip: AnimationClip, root: RootMotionNode): AnimationSamplerData | null {
  return clip.channels.find((c) => c.node === root.node && c.path === 'translation')?.sampler ?? null;
}

/** Model-space horizontal displacement of the root between clip time 0 and `timeS`. */
function horizontalDisplacement(sampler: AnimationSamplerData, root: RootMotionNode, timeS: number): Vec3 {
  const start = [0, 0, 0];
  const now = [0, 0, 0];
  sampleAnimationSampler(sampler, 0, false, start);
  sampleAnimationSampler(sampler, timeS, false, now);
  const local = [now[0] - start[0], now[1] - start[1], now[2] - start[2]];
  const p = root.parentLinear;
  // wgpu-matrix mat3 is column-major with a padded 4th row: element (r, c) at 4c + r.
  const x = p[0] * local[0] + p[4] * local[1] + p[8] * local[2];
  const z = p[2] * local[0] + p[6] * local[1] + p[10] * local[2];
  return [x, 0, z];
}

/** Horizontal distance the clip's root travels over one loop (time 0 to the clip duration), in model units. */
export function measureRootMotionPerLoop(clip: AnimationClip, root: RootMotionNode | null): number {
  if (root === null) return 0;
  const sampler = rootTranslationSampler(clip, root);
  if (sampler === null) return 0;
  const d = horizontalDisplacement(sampler, root, clip.durationS);
  return Math.hypot(d[0], d[2]);
}

/**
 * Makes a clip pose "in place": subtracts the root's horizontal model-space displacement since
 * clip time 0 from its local translation, keeping vertical motion (bobbing, jumps) as authored.
 */
export function removeHorizontalRootMotion(pose: Pose, clip: AnimationClip, root: RootMotionNode | null, clipTimeS: number): void {
  if (root === null) return;
  const sampler = rootTranslationSampler(clip, root);
  if (sampler === null) return;
  const d = horizontalDisplacement(sampler, root, clipTimeS);
  const q = root.parentLinearInverse;
  const o = 3 * root.node;
  pose.translations[o] -= q[0] * d[0] + q[8] * d[2];
  pose.translations[o + 1] -= q[1] * d[0] + q[9] * d[2];
  pose.translations[o + 2] -= q[2] * d[0] + q[10] * d[2];
}
