import { vec3d } from 'wgpu-matrix';
import { fail } from '../../errors/validate.ts';
import type { AnimatedModel, Vec3 } from '../model/model-types.ts';
import { evaluateLayeredPose } from '../pose/evaluate-layers.ts';
import { createRestPose } from '../pose/pose.ts';
import { computeWorldMatrices } from '../pose/world-matrices.ts';
import type { SceneTimeline } from '../timeline/scene-timeline.ts';
import type { CameraSubject } from './camera-types.ts';

/**
 * The head anchor joint: `name` when given (an error naming `field` when missing), else the first
 * node named "Head" or ending in ":Head" / "_Head" (Mixamo's "mixamorig:Head"), preferring joints;
 * -1 when there is none.
 */
export function findHeadAnchor(model: Pick<AnimatedModel, 'nodes' | 'skins'>, name?: string, field = 'camera.headJoint'): number {
  if (name !== undefined) {
    const index = model.nodes.findIndex((n) => n.name === name);
    if (index < 0) fail('INVALID_OPTION', field, `the model has no node named ${JSON.stringify(name)}`);
    return index;
  }
  const isHead = (n: { name: string }): boolean => /(^|[:_|.])head$/i.test(n.name);
  const joints = new Set(model.skins.flatMap((s) => [...s.joints]));
  const candidates = model.nodes.map((n, i) => ({ n, i })).filter(({ n }) => isHead(n));
  return (candidates.find(({ i }) => joints.has(i)) ?? candidates[0])?.i ?? -1;
}

export interface CharacterCameraSubject extends CameraSubject {
  /** Head anchor node index or -1. */
  readonly headNode: number;
  readonly focusHeight: number;
}

/**
 * What the camera follows for an animated character: the focus point (character position plus
 * `focusHeight`, default the head's rest height), velocity and heading from the timeline, and the
 * head anchor from the animated pose (the joint's origin in world space, after animation).
 */
export function createCharacterCameraSubject(model: AnimatedModel, timeline: SceneTimeline, options: { headJoint?: string; focusHeight?: number } = {}): CharacterCameraSubject {
  const headNode = findHeadAnchor(model, options.headJoint);
  let focusHeight = options.focusHeight ?? 1;
  if (options.focusHeight === undefined && headNode >= 0) {
    const world = computeWorldMatrices(model, createRestPose(model));
    focusHeight = world[16 * headNode + 13];
  }
  let cached: { tMs: number; head: Vec3 } | null = null;
  return {
    headNode,
    focusHeight,
    focusAt: (tMs) => {
      const p = timeline.characterAt(tMs).position;
      return [p[0], p[1] + focusHeight, p[2]];
    },
    velocityAt: (tMs) => timeline.characterAt(tMs).velocity,
    yawAt: (tMs) => timeline.characterAt(tMs).yaw,
    headAnchorAt: (tMs) => {
      if (headNode < 0) return null;
      if (cached?.tMs === tMs) return cached.head;
      const sample = timeline.sample(tMs);
      const world = computeWorldMatrices(model, evaluateLayeredPose(model, sample.layers));
      const local = [world[16 * headNode + 12], world[16 * headNode + 13], world[16 * headNode + 14]];
      const head = [...vec3d.transformMat4(local, sample.rootTransform)] as Vec3;
      cached = { tMs, head };
      return head;
    },
  };
}
