/**
 * Posing a glTF asset at one instant of one of its animations (glTF 2.0 sections 3.5.3, 3.7.2.2,
 * 3.7.3 and 3.11): which animation, then every node's world matrix, every mesh node's morph
 * weights and every skin's joint matrices at that time. The keyframe sampling, pose and joint
 * arithmetic is src/animation's, the code the raster renderer poses with, so both renderers pose
 * an asset identically. Errors of that module (dotted fields) become the loader's INVALID_GLTF
 * errors with JSON pointers.
 */
import type { Document, Node } from '@gltf-transform/core';
import { checkClipTargets } from '../../animation/clips/bind-clips.ts';
import type { AnimationClip } from '../../animation/clips/clip-types.ts';
import { readAnimationClips } from '../../animation/clips/read-clips.ts';
import type { ModelNode, ModelSkin } from '../../animation/model/model-types.ts';
import { readNodeHierarchy, readNodeRest } from '../../animation/model/read-node-hierarchy.ts';
import { readSkins } from '../../animation/model/read-skins.ts';
import { evaluateClipPose } from '../../animation/pose/evaluate-clip.ts';
import { createRestPose } from '../../animation/pose/pose.ts';
import { computeJointMatrices, computeWorldMatrices } from '../../animation/pose/world-matrices.ts';
import { GpuRendererError, isGpuRendererError } from '../../errors/gpu-renderer-error.ts';
import { dottedFieldToPointer, failGltf, pointer } from './errors.ts';

/** One animation of the asset. */
export interface GltfAnimationInfo {
  /** Index in the asset (`/animations/i`). */
  readonly index: number;
  /** The animation's name; '' when it has none. */
  readonly name: string;
  /** The last keyframe time over its channels, in seconds. */
  readonly durationS: number;
}

/** Which animation to pose and when. */
export interface GltfPoseOptions {
  /**
   * The animation: its index (`/animations/i`) or name. Default the asset's first animation;
   * `null` poses no animation (every node at its authored transform, morph weights at their defaults).
   */
  animation?: number | string | null;
  /**
   * Seconds into the animation; default 0. Before the first and after the last keyframe the
   * animation holds its first / last values (glTF 2.0 section 3.11); it does not loop.
   */
  time?: number;
}

/** The asset's node forest, skins and animations, read and validated once. */
export interface GltfRig {
  readonly nodes: readonly ModelNode[];
  readonly nodeOrder: Int32Array;
  readonly skins: readonly ModelSkin[];
  readonly clips: readonly AnimationClip[];
  readonly animations: readonly GltfAnimationInfo[];
}

/** The rig at one instant. */
export interface GltfPose {
  /** The animation posed; null for none. */
  readonly animation: GltfAnimationInfo | null;
  readonly time: number;
  /** World matrix of node `n` (column-major). */
  world(node: number): Float64Array;
  /** Morph weights of node `n` (empty for a node without morph targets). */
  weights(node: number): Float64Array;
  /** Joint matrices of skin `s` (16 per joint): world(joint) x inverse bind matrix. */
  jointMatrices(skin: number): Float64Array;
}

/** Runs `read`, turning src/animation's INVALID_MODEL / INVALID_ANIMATION errors into INVALID_GLTF with pointers. */
export function withGltfPointers<T>(read: () => T): T {
  try {
    return read();
  } catch (error) {
    if (!isGpuRendererError(error) || (error.code !== 'INVALID_MODEL' && error.code !== 'INVALID_ANIMATION') || error.field === undefined) throw error;
    const message = error.message.startsWith(`${error.field}: `) ? error.message.slice(error.field.length + 2) : error.message;
    throw new GpuRendererError('INVALID_GLTF', message, { field: dottedFieldToPointer(error.field), cause: error });
  }
}

/** The asset poses only when it animates something or skins a mesh; otherwise nodes keep their matrices. */
export function needsRig(document: Document): boolean {
  const root = document.getRoot();
  return root.listAnimations().length > 0 || root.listSkins().length > 0;
}

function targetCountOf(node: Node): number {
  return node.getMesh()?.listPrimitives()[0]?.listTargets().length ?? 0;
}

/** Reads the node forest with rest transforms and default morph weights, the skins and the animations. */
export function readRig(document: Document): GltfRig {
  return withGltfPointers(() => {
    const root = document.getRoot();
    const hierarchy = readNodeHierarchy(document, '');
    const meshIndex = new Map(root.listMeshes().map((mesh, i) => [mesh, i]));
    const skinIndex = new Map(root.listSkins().map((skin, i) => [skin, i]));
    const nodes: ModelNode[] = hierarchy.nodes.map((node, i) => {
      const mesh = node.getMesh();
      const skin = node.getSkin();
      const targetCount = targetCountOf(node);
      const own = node.getWeights();
      const defaults = mesh?.getWeights() ?? [];
      // Section 3.7.2.2: node.weights, else mesh.weights, else zeros; one weight per morph target.
      for (const [weights, at] of [[own, pointer('nodes', i, 'weights')], [defaults, pointer('meshes', mesh === null ? -1 : (meshIndex.get(mesh) ?? -1), 'weights')]] as const) {
        if (weights.length !== 0 && weights.length !== targetCount) failGltf(at, `${weights.length} weights for ${targetCount} morph targets`);
        weights.forEach((w, k) => {
          if (!Number.isFinite(w)) failGltf(`${at}/${k}`, `expected a finite number, got ${w}`);
        });
      }
      const weights = own.length > 0 ? [...own] : defaults.length > 0 ? [...defaults] : new Array<number>(targetCount).fill(0);
      return {
        name: node.getName(),
        parent: hierarchy.parents[i],
        children: hierarchy.children[i],
        ...readNodeRest(node, `nodes[${i}]`),
        mesh: mesh === null ? -1 : (meshIndex.get(mesh) ?? -1),
        skin: skin === null ? -1 : (skinIndex.get(skin) ?? -1),
        weights,
      };
    });
    const skins = readSkins(document, hierarchy.indexOf, '');
    const clips = readAnimationClips(document, hierarchy.indexOf, '');
    const meshes = root.listMeshes().map((mesh) => ({ targetCount: mesh.listPrimitives()[0]?.listTargets().length ?? 0 }));
    for (const clip of clips) checkClipTargets({ nodes, meshes }, clip);
    const animations = clips.map((clip, index) => ({ index, name: clip.name, durationS: clip.durationS }));
    return { nodes, nodeOrder: hierarchy.order, skins, clips, animations };
  });
}

function optionError(field: string, message: string): GpuRendererError {
  return new GpuRendererError('INVALID_OPTION', message, { field });
}

/** The animation `choice` names (default the first; null none); unknown names and indices are INVALID_OPTION errors. */
export function chooseAnimation(animations: readonly GltfAnimationInfo[], choice: number | string | null | undefined): GltfAnimationInfo | null {
  if (choice === null) return null;
  if (choice === undefined) return animations[0] ?? null;
  const known = animations.map((a) => `${a.index} ${JSON.stringify(a.name)}`).join(', ') || 'none';
  if (typeof choice === 'number') {
    const found = Number.isInteger(choice) ? animations[choice] : undefined;
    if (found === undefined) throw optionError('animation', `animation index ${choice} is out of range (animations: ${known})`);
    return found;
  }
  if (typeof choice !== 'string') throw optionError('animation', 'expected an animation index, a name or null');
  const found = animations.find((a) => a.name === choice);
  if (found === undefined) throw optionError('animation', `no animation named ${JSON.stringify(choice)} (animations: ${known})`);
  return found;
}

/** The time option: a finite number of seconds >= 0. */
export function poseTime(time: unknown): number {
  if (time === undefined) return 0;
  if (typeof time !== 'number' || !Number.isFinite(time) || time < 0) throw optionError('time', `expected a finite number of seconds >= 0, got ${String(time)}`);
  return time;
}

/** Poses the rig: `options.animation` sampled at `options.time` (defaults: the first animation, 0 s). */
export function poseRig(rig: GltfRig, options: GltfPoseOptions = {}): GltfPose {
  const animation = chooseAnimation(rig.animations, options.animation);
  const time = poseTime(options.time);
  const pose = animation === null ? createRestPose(rig) : evaluateClipPose(rig, rig.clips[animation.index]!, time);
  const world = computeWorldMatrices(rig, pose);
  const joints = new Map<number, Float64Array>();
  return {
    animation,
    time,
    world: (node) => world.subarray(16 * node, 16 * node + 16),
    weights: (node) => pose.weights[node]!,
    jointMatrices: (skin) => {
      let matrices = joints.get(skin);
      if (matrices === undefined) joints.set(skin, (matrices = computeJointMatrices(rig, skin, world)));
      return matrices;
    },
  };
}
