import type { Document } from '@gltf-transform/core';
import { fail } from '../errors/validate.ts';
import { createCameraController, type CameraController } from './camera/camera-controller.ts';
import type { AnimatedCameraOptionsInput } from './camera/camera-options.ts';
import { createCharacterCameraSubject, type CharacterCameraSubject } from './camera/camera-subject.ts';
import type { CameraRigOutput, CameraViewMode } from './camera/camera-types.ts';
import { requireProfessionalCharacter, requireSkinnedCharacter } from './character-requirements.ts';
import { createClipLibrary, type ClipAssetInput, type ClipLibrary } from './clips/clip-library.ts';
import type { AnimatedModel } from './model/model-types.ts';
import { readAnimatedModel } from './model/read-model.ts';
import { evaluateLayeredPose } from './pose/evaluate-layers.ts';
import type { Pose } from './pose/pose.ts';
import { computeJointMatrices, computeWorldMatrices } from './pose/world-matrices.ts';
import { bakePose, type BakedPose, type BakePoseOptions } from './skinning/bake-pose.ts';
import { assembleAnimationSnapshot, type AnimationSnapshotCore } from './snapshot/animation-snapshot.ts';
import type { AnimationBeatInput } from './timeline/beats.ts';
import type { MovementTolerances } from './timeline/movement.ts';
import type { RoutePointInput } from './timeline/route.ts';
import { createSceneTimeline, type SceneTimeline, type TimelineSample } from './timeline/scene-timeline.ts';
import type { PropInput, TerrainHeight } from './timeline/terrain.ts';

/** The animated scene's renderer-independent options (names as in createAnimatedSceneRenderer). */
export interface AnimatedSceneCoreOptions {
  /** The character: a glTF document with a skinned mesh. */
  modelAsset: Document;
  /** Clips by id with movement profiles; default every animation of the model, by name. */
  clipAssets?: readonly ClipAssetInput[];
  beats: readonly AnimationBeatInput[];
  route: readonly RoutePointInput[];
  props?: readonly PropInput[];
  camera?: AnimatedCameraOptionsInput;
  /** Ground height under (x, z); default flat ground at y = 0. */
  terrain?: TerrainHeight;
  tolerances?: MovementTolerances;
  /** Enforce the professional renderer's fail-closed model and clip requirements. */
  professional?: boolean;
}

/** Everything a renderer needs to draw one frame. */
export interface AnimatedSceneFrame {
  readonly snapshot: AnimationSnapshotCore;
  readonly sample: TimelineSample;
  readonly camera: CameraRigOutput;
  readonly pose: Pose;
  /** Model-space world matrix of every node (16 per node, column-major). */
  readonly worldMatrices: Float64Array;
  /** Per skin, joint matrices (16 floats per joint, column-major) ready for upload. */
  readonly jointMatrices: Float32Array[];
  /** Per drawable (model.drawables order), its morph weights. */
  readonly morphWeights: Float32Array[];
}

export interface AnimatedSceneCore {
  readonly model: AnimatedModel;
  readonly library: ClipLibrary;
  readonly timeline: SceneTimeline;
  readonly subject: CharacterCameraSubject;
  readonly camera: CameraController;
  /** Evaluates the scene at `tMs` and counts a frame. */
  frame(tMs: number): AnimatedSceneFrame;
  /** The snapshot of the last frame, or null before the first. */
  getSnapshot(): AnimationSnapshotCore | null;
  setCamera(options: AnimatedCameraOptionsInput): void;
  setCameraViewMode(mode: CameraViewMode): void;
  applyCameraControl(control: unknown): void;
  /** The posed character at `tMs` as scene meshes and instances, for the path tracer. */
  bakePose(tMs: number, options?: BakePoseOptions): BakedPose;
}

/**
 * Composes the animation core for one animated scene: reads and validates the model, binds the
 * clips, lays out beats, movement and props, and sets up the camera rigs. Pure CPU; the raster
 * renderer wraps it and uploads `frame()`'s matrices and weights.
 */
export function createAnimatedSceneCore(options: AnimatedSceneCoreOptions): AnimatedSceneCore {
  if (typeof options !== 'object' || options === null) fail('INVALID_OPTION', 'options', 'expected an options object');
  const document = options.modelAsset as unknown;
  if (typeof document !== 'object' || document === null || typeof (document as Document).getRoot !== 'function') {
    fail('INVALID_OPTION', 'modelAsset', 'expected a glTF Document (@gltf-transform/core)');
  }
  const model = readAnimatedModel(options.modelAsset, { field: 'modelAsset' });
  requireSkinnedCharacter(model);
  const library = createClipLibrary(model, options.clipAssets);
  const timeline = createSceneTimeline(library, { beats: options.beats, route: options.route, props: options.props, terrain: options.terrain, tolerances: options.tolerances });
  if (options.professional) requireProfessionalCharacter(model, library, timeline.beats);
  const subject = createCharacterCameraSubject(model, timeline, { headJoint: options.camera?.headJoint, focusHeight: options.camera?.focusHeight });
  const camera = createCameraController(options.camera, { hasHeadAnchor: subject.headNode >= 0 });
  let frameCount = 0;
  let snapshot: AnimationSnapshotCore | null = null;
  return {
    model,
    library,
    timeline,
    subject,
    camera,
    frame(tMs) {
      const sample = timeline.sample(tMs);
      const pose = evaluateLayeredPose(model, sample.layers);
      const worldMatrices = computeWorldMatrices(model, pose);
      const jointMatrices = model.skins.map((_, s) => Float32Array.from(computeJointMatrices(model, s, worldMatrices)));
      const morphWeights = model.drawables.map((d) => Float32Array.from(pose.weights[d.node]));
      const rig = camera.evaluate(tMs, subject);
      frameCount++;
      snapshot = assembleAnimationSnapshot({ frame: frameCount, model, timeline, sample, camera: rig });
      return { snapshot, sample, camera: rig, pose, worldMatrices, jointMatrices, morphWeights };
    },
    getSnapshot: () => snapshot,
    setCamera: (input) => camera.setCamera(input),
    setCameraViewMode: (mode) => camera.setViewMode(mode),
    applyCameraControl: (control) => camera.applyControl(control),
    bakePose: (tMs, bakeOptions) => bakePose(model, timeline, tMs, bakeOptions),
  };
}
