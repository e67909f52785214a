import { fail, requireFiniteNumber } from '../../errors/validate.ts';
import type { Vec3 } from '../model/model-types.ts';
import { add, cameraTransform, directionFromYawPitch, distance, lerp3, scale, yawPitchFromDirection } from './camera-math.ts';
import { validateCameraOptions, validateViewMode, type CameraSettings } from './camera-options.ts';
import type { CameraControlInput, CameraRigOutput, CameraSubject, CameraTransform, CameraViewMode, HeadLookIntent } from './camera-types.ts';
import { cubicBezierEasing } from './cubic-bezier.ts';
import { createLaggedFollow, type LaggedFollow } from './lagged-follow.ts';
import {
  applyEditorControl, applyLookControl, applySpectatorControl, applyThirdPersonControl, constrainThirdPerson,
  editorTransform, flyFromPose, orbitFromPose, spectatorTransform, type FlyState, type LookState, type OrbitState,
} from './rigs.ts';

export interface CameraController {
  readonly viewMode: CameraViewMode;
  readonly settings: CameraSettings;
  /** Switches rig; with transitionMs > 0 the camera eases from its last transform over transitionMs. */
  setViewMode(mode: CameraViewMode): void;
  /** Partial update of the camera options (validated like the constructor's). */
  setCamera(options: unknown): void;
  /** Relative input to the current rig; third-person `look` and first-person `look`/`orbit` steer head-look. */
  applyControl(control: unknown): void;
  /** Camera at scene time `tMs` following `subject`. */
  evaluate(tMs: number, subject: CameraSubject): CameraRigOutput;
}

export interface CameraControllerContext {
  /** Whether the model has a head anchor joint (first-person needs one). */
  hasHeadAnchor: boolean;
  field?: string;
}

function validateControl(control: unknown): CameraControlInput {
  if (typeof control !== 'object' || control === null) fail('INVALID_OPTION', 'control', 'expected a camera control object');
  const c = control as Record<string, unknown>;
  const pair = (key: string, length: number): number[] | undefined => {
    const v = c[key];
    if (v === undefined) return undefined;
    if (!Array.isArray(v) || v.length !== length) fail('INVALID_OPTION', `control.${key}`, `expected ${length} numbers`);
    return v.map((x, i) => requireFiniteNumber(x, `control.${key}[${i}]`));
  };
  const out: CameraControlInput = {};
  const orbit = pair('orbit', 2);
  const pan = pair('pan', 2);
  const look = pair('look', 2);
  const move = pair('move', 3);
  if (orbit) out.orbit = orbit as [number, number];
  if (pan) out.pan = pan as [number, number];
  if (look) out.look = look as [number, number];
  if (move) out.move = move as [number, number, number];
  if (c.zoom !== undefined) out.zoom = requireFiniteNumber(c.zoom, 'control.zoom');
  return out;
}

/**
 * The animated scene's camera: the four rig primitives behind one view mode, the lagged-follow rig
 * driving third-person, constraints (third-person distance in [minDistance, maxDistance], pitch
 * limits, head-look limits), eased view transitions and the head-look intent report.
 */
export function createCameraController(options: unknown, context: CameraControllerContext): CameraController {
  const field = context.field ?? 'camera';
  let settings = validateCameraOptions(options, field);
  let follow: LaggedFollow = createLaggedFollow(settings.lagMs);
  let ease = cubicBezierEasing(settings.cubicBezier);
  const thirdFromOffset = (): { yaw: number; pitch: number; distance: number } => {
    const { yaw, pitch, length } = yawPitchFromDirection(settings.offset);
    return constrainThirdPerson({ yaw, pitch, distance: length }, settings);
  };
  let third = thirdFromOffset();
  let editor: OrbitState | null = null;
  let spectator: FlyState | null = null;
  let firstPersonLook: LookState = { yaw: 0, pitch: 0 };
  let headLook: LookState = { yaw: 0, pitch: 0 };
  let viewMode: CameraViewMode = 'third-person';
  let last: { tMs: number; transform: CameraTransform } | null = null;
  let transition: { from: CameraTransform; startMs: number } | null = null;

  const poseFromSettings = (): { position: Vec3; target: Vec3 } | null =>
    settings.position !== null && settings.target !== null ? { position: settings.position, target: settings.target } : null;
  const ensureFreeRigs = (): void => {
    const pose = poseFromSettings() ?? (last ? { position: last.transform.position, target: last.transform.target } : { position: add([0, 1, 0], settings.offset), target: [0, 1, 0] as Vec3 });
    editor ??= orbitFromPose(pose.position, pose.target);
    spectator ??= flyFromPose(pose.position, pose.target);
  };
  const setViewMode = (mode: unknown): void => {
    const next = validateViewMode(mode, `${field}.viewMode`);
    if (next === 'first-person' && !context.hasHeadAnchor) fail('INVALID_MODEL', `${field}.headJoint`, 'first-person needs a head anchor joint; the model has none (name one with camera.headJoint)');
    settings = { ...settings, viewMode: next };
    if (next === viewMode) return;
    if (next === 'editor' || next === 'spectator') ensureFreeRigs();
    transition = last !== null && settings.transitionMs > 0 ? { from: last.transform, startMs: last.tMs } : null;
    viewMode = next;
  };
  setViewMode(settings.viewMode);

  return {
    get viewMode() {
      return viewMode;
    },
    get settings() {
      return settings;
    },
    setViewMode,
    setCamera(input) {
      const previous = settings;
      settings = validateCameraOptions(input, field, settings);
      if (settings.lagMs !== previous.lagMs) follow = createLaggedFollow(settings.lagMs);
      if (settings.cubicBezier !== previous.cubicBezier) ease = cubicBezierEasing(settings.cubicBezier);
      third = settings.offset !== previous.offset ? thirdFromOffset() : constrainThirdPerson(third, settings);
      const pose = poseFromSettings();
      if (pose !== null && (settings.position !== previous.position || settings.target !== previous.target)) {
        editor = orbitFromPose(pose.position, pose.target);
        spectator = flyFromPose(pose.position, pose.target);
      }
      if (settings.viewMode !== viewMode) setViewMode(settings.viewMode);
    },
    applyControl(input) {
      const control = validateControl(input);
      switch (viewMode) {
        case 'editor':
          ensureFreeRigs();
          editor = applyEditorControl(editor!, control);
          break;
        case 'spectator':
          ensureFreeRigs();
          spectator = applySpectatorControl(spectator!, control);
          break;
        case 'third-person':
          third = applyThirdPersonControl(third, control, settings);
          if (control.look) headLook = applyLookControl(headLook, control.look, settings.headYawLimit, settings.headPitchLimit);
          break;
        case 'first-person': {
          const look = control.look ?? control.orbit;
          if (look) firstPersonLook = applyLookControl(firstPersonLook, look, settings.headYawLimit, settings.headPitchLimit);
          break;
        }
      }
    },
    evaluate(tMs, subject) {
      let transform: CameraTransform;
      let targetDistance: number;
      const heading = subject.yawAt(tMs);
      switch (viewMode) {
        case 'third-person': {
          const pivot = follow.valueAt(tMs, (t) => subject.focusAt(t));
          const lookTarget = add(pivot, scale(subject.velocityAt(tMs), settings.lookAheadMs / 1000));
          const position = add(pivot, scale(directionFromYawPitch(third.yaw, third.pitch), third.distance));
          transform = cameraTransform(position, lookTarget, settings.fovYDegrees);
          targetDistance = distance(position, pivot);
          break;
        }
        case 'first-person': {
          const head = subject.headAnchorAt(tMs);
          if (head === null) fail('INVALID_MODEL', `${field}.headJoint`, 'first-person needs a head anchor joint');
          transform = cameraTransform(head, add(head, directionFromYawPitch(heading + firstPersonLook.yaw, firstPersonLook.pitch)), settings.fovYDegrees);
          targetDistance = 0;
          break;
        }
        case 'editor':
          ensureFreeRigs();
          transform = editorTransform(editor!, settings.fovYDegrees);
          targetDistance = editor!.distance;
          break;
        case 'spectator':
          ensureFreeRigs();
          transform = spectatorTransform(spectator!, settings.fovYDegrees);
          targetDistance = distance(spectator!.position, subject.focusAt(tMs));
          break;
      }
      let transitionProgress = 1;
      if (transition !== null) {
        const u = (tMs - transition.startMs) / settings.transitionMs;
        if (u >= 1 || u < 0) transition = null;
        else {
          transitionProgress = ease(u);
          const from = transition.from;
          transform = cameraTransform(lerp3(from.position, transform.position, transitionProgress), lerp3(from.target, transform.target, transitionProgress), settings.fovYDegrees);
        }
      }
      const look = viewMode === 'first-person' ? firstPersonLook : viewMode === 'third-person' ? headLook : { yaw: 0, pitch: 0 };
      const intent: HeadLookIntent = {
        active: look.yaw !== 0 || look.pitch !== 0,
        yaw: look.yaw,
        pitch: look.pitch,
        direction: directionFromYawPitch(heading + look.yaw, look.pitch),
      };
      last = { tMs, transform };
      return { viewMode, transform, targetDistance, headLook: intent, transitionProgress };
    },
  };
}
