import type { Vec3 } from '../model/model-types.ts';

/** The four rig primitives (the 0.2 API's editor, spectator, third-person and first-person rigs). */
export type CameraViewMode = 'editor' | 'spectator' | 'third-person' | 'first-person';

export const CAMERA_VIEW_MODES: readonly CameraViewMode[] = ['editor', 'spectator', 'third-person', 'first-person'];

export interface CameraTransform {
  readonly position: Vec3;
  readonly target: Vec3;
  readonly up: Vec3;
  /** Unit vector from position towards target. */
  readonly forward: Vec3;
  readonly fovYDegrees: number;
  /** World-to-view matrix, column-major (right-handed, looking down -Z). */
  readonly viewMatrix: number[];
}

/**
 * Where the character wants to look, reported after animation as transient intent: yaw and pitch
 * relative to the character's heading, never written into clip data. A renderer may add it to the
 * head joint after evaluating the pose.
 */
export interface HeadLookIntent {
  readonly active: boolean;
  readonly yaw: number;
  readonly pitch: number;
  /** World-space unit look direction. */
  readonly direction: Vec3;
}

/** What the rigs follow: the character's focus point, velocity, heading and head anchor over time. */
export interface CameraSubject {
  /** Point the follow rigs orbit and aim at (character position plus focus height). */
  focusAt(tMs: number): Vec3;
  /** Metres per second. */
  velocityAt(tMs: number): Vec3;
  /** Heading about +Y (0 faces +Z). */
  yawAt(tMs: number): number;
  /** World position of the head anchor joint, or null when the model has none. */
  headAnchorAt(tMs: number): Vec3 | null;
}

/** Relative camera input (radians, metres). Each view mode uses the inputs that make sense for it. */
export interface CameraControlInput {
  /** Orbit yaw and pitch deltas (editor, third-person; first-person treats it as look). */
  orbit?: readonly [number, number];
  /** Metres towards the target (editor, third-person distance; spectator moves forward). */
  zoom?: number;
  /** View-plane pan right and up (editor moves the pivot, spectator moves the camera). */
  pan?: readonly [number, number];
  /** Look yaw and pitch deltas (spectator, first-person view; third-person head-look). */
  look?: readonly [number, number];
  /** Spectator fly: forward, right, up in metres. */
  move?: readonly [number, number, number];
}

export interface CameraRigOutput {
  readonly viewMode: CameraViewMode;
  readonly transform: CameraTransform;
  /** Distance from the camera to the point its rig pivots on (third-person: the clamped follow distance). */
  readonly targetDistance: number;
  readonly headLook: HeadLookIntent;
  /** Eased progress of a view-mode transition, 1 when none is running. */
  readonly transitionProgress: number;
}
