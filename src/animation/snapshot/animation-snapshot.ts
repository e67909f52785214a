import type { CameraRigOutput, CameraTransform, CameraViewMode, HeadLookIntent } from '../camera/camera-types.ts';
import type { AnimatedModel, Vec3 } from '../model/model-types.ts';
import type { MovementDiagnostic } from '../timeline/movement.ts';
import type { SceneTimeline, TimelineSample } from '../timeline/scene-timeline.ts';
import type { PropGroundAnchor } from '../timeline/terrain.ts';

/** Result of movement validation: `valid` when the beats, clips and route agree (no diagnostics). */
export interface MovementValidation {
  readonly mode: 'per-beat' | 'route-timed';
  readonly valid: boolean;
  readonly diagnostics: readonly MovementDiagnostic[];
  /** Time each route anchor is reached (null: never). */
  readonly anchorArrivalsMs: readonly (number | null)[];
}

/**
 * The renderer-independent part of the animated scene snapshot (the 0.2 API's field
 * names, which hosts check). The GPU renderer adds what only it knows: modelRenderable, activeClipRenderable,
 * characterVisible, render mode and texture readiness.
 */
export interface AnimationSnapshotCore {
  readonly frame: number;
  readonly timeMs: number;
  readonly activeClipId: string;
  readonly activeBeatId: string;
  readonly blendProgress: number;
  readonly clipTimeMs: number;
  readonly characterPosition: Vec3;
  readonly characterGroundY: number;
  readonly characterYaw: number;
  readonly cameraViewMode: CameraViewMode;
  readonly cameraPosition: Vec3;
  readonly cameraTransform: CameraTransform;
  readonly targetDistance: number;
  readonly headLook: HeadLookIntent;
  readonly skinnedVertexCount: number;
  readonly skinnedJointCount: number;
  readonly propGroundAnchors: readonly PropGroundAnchor[];
  readonly movementValidation: MovementValidation;
  /** There is no 2D proxy character: always false. */
  readonly fallbackProxyActive: false;
}

/** Vertices the skinned drawables deform per frame (a mesh drawn by two skinned nodes counts twice). */
export function countSkinnedVertices(model: AnimatedModel): number {
  let count = 0;
  for (const drawable of model.drawables) {
    if (drawable.skin < 0) continue;
    for (const primitive of model.meshes[drawable.mesh].primitives) count += primitive.vertexCount;
  }
  return count;
}

/** Distinct joint nodes of the skins that skinned drawables use. */
export function countSkinnedJoints(model: AnimatedModel): number {
  const joints = new Set<number>();
  for (const drawable of model.drawables) if (drawable.skin >= 0) for (const j of model.skins[drawable.skin].joints) joints.add(j);
  return joints.size;
}

export function movementValidation(timeline: SceneTimeline): MovementValidation {
  const plan = timeline.movement;
  return { mode: plan.mode, valid: plan.diagnostics.length === 0, diagnostics: plan.diagnostics, anchorArrivalsMs: plan.anchorArrivalsMs };
}

export function assembleAnimationSnapshot(input: {
  frame: number;
  model: AnimatedModel;
  timeline: SceneTimeline;
  sample: TimelineSample;
  camera: CameraRigOutput;
}): AnimationSnapshotCore {
  const { sample, camera } = input;
  return {
    frame: input.frame,
    timeMs: sample.tMs,
    activeClipId: sample.activeClipId,
    activeBeatId: sample.activeBeatId,
    blendProgress: sample.blendProgress,
    clipTimeMs: sample.clipTimeMs,
    characterPosition: sample.position,
    characterGroundY: sample.groundY,
    characterYaw: sample.yaw,
    cameraViewMode: camera.viewMode,
    cameraPosition: camera.transform.position,
    cameraTransform: camera.transform,
    targetDistance: camera.targetDistance,
    headLook: camera.headLook,
    skinnedVertexCount: countSkinnedVertices(input.model),
    skinnedJointCount: countSkinnedJoints(input.model),
    propGroundAnchors: input.timeline.propGroundAnchors,
    movementValidation: movementValidation(input.timeline),
    fallbackProxyActive: false,
  };
}
