import { mat4d } from 'wgpu-matrix';
import { fail } from '../../errors/validate.ts';
import type { ClipLibrary } from '../clips/clip-library.ts';
import type { Vec3 } from '../model/model-types.ts';
import type { ClipLayer } from '../pose/evaluate-layers.ts';
import type { PoseSource } from '../skinning/bake-pose.ts';
import { scheduleBeats, type AnimationBeat } from './beats.ts';
import { beatLayersAt } from './clip-layers.ts';
import { movementDistanceAt, movementSpeedAt, resolveMovement, type MovementPlan, type MovementTolerances } from './movement.ts';
import { routePointAt, validateRoute, type Route } from './route.ts';
import { flatTerrain, groundHeight, groundProps, type PropGroundAnchor, type TerrainHeight } from './terrain.ts';

export interface SceneTimelineOptions {
  beats: unknown;
  route: unknown;
  props?: unknown;
  /** Ground height under (x, z); default flat ground at y = 0. */
  terrain?: TerrainHeight;
  tolerances?: MovementTolerances;
}

/** The character's placement at one instant. */
export interface CharacterPlacement {
  /** On the ground: (x, groundY, z). */
  readonly position: Vec3;
  readonly groundY: number;
  /** Heading about +Y; 0 faces +Z (glTF's forward for assets). */
  readonly yaw: number;
  /** Horizontal velocity, metres per second. */
  readonly velocity: Vec3;
  /** Column-major model-to-world matrix: translation(position) x rotationY(yaw). */
  readonly rootTransform: Float64Array;
}

export interface TimelineSample extends CharacterPlacement {
  readonly tMs: number;
  readonly activeBeatId: string;
  readonly activeClipId: string;
  readonly clipTimeMs: number;
  readonly blendProgress: number;
  readonly layers: readonly ClipLayer[];
}

export interface SceneTimeline extends PoseSource {
  readonly beats: readonly AnimationBeat[];
  readonly route: Route;
  readonly movement: MovementPlan;
  readonly propGroundAnchors: readonly PropGroundAnchor[];
  /** Sum of beat durations. */
  readonly durationMs: number;
  readonly terrain: TerrainHeight;
  characterAt(tMs: number): CharacterPlacement;
  sample(tMs: number): TimelineSample;
}

/**
 * The renderer-independent scene clock: beats laid out in order with cross-fades, the character's
 * movement along the route and its grounding, props on the terrain. Everything is a pure function
 * of the scene time, so a raster preview and a path-traced still at the same time agree.
 */
export function createSceneTimeline(library: ClipLibrary, options: SceneTimelineOptions): SceneTimeline {
  const terrain = options.terrain ?? flatTerrain;
  if (typeof terrain !== 'function') fail('INVALID_OPTION', 'terrain', 'expected a function (x, z) => ground height');
  const beats = scheduleBeats(options.beats, library);
  const route = validateRoute(options.route);
  const propGroundAnchors = groundProps(options.props, terrain);
  const movement = resolveMovement(beats, route, terrain, options.tolerances);
  const durationMs = beats[beats.length - 1].endMs;

  const characterAt = (tMs: number): CharacterPlacement => {
    const t = Math.max(0, tMs);
    const distance = movementDistanceAt(movement, route, t);
    const point = routePointAt(route, distance);
    const groundY = groundHeight(terrain, point.x, point.z);
    const speed = movementSpeedAt(movement, route, t) * 1000;
    const velocity: Vec3 = [speed * Math.sin(point.yaw), 0, speed * Math.cos(point.yaw)];
    const rootTransform = mat4d.rotateY(mat4d.translation([point.x, groundY, point.z]), point.yaw);
    return { position: [point.x, groundY, point.z], groundY, yaw: point.yaw, velocity, rootTransform };
  };

  const sample = (tMs: number): TimelineSample => {
    const layers = beatLayersAt(beats, movement, tMs);
    const beat = beats[layers.activeIndex];
    return {
      tMs,
      activeBeatId: beat.id,
      activeClipId: beat.clip.id,
      clipTimeMs: layers.activeClipTimeMs,
      blendProgress: layers.blendProgress,
      layers: layers.layers,
      ...characterAt(tMs),
    };
  };

  return {
    beats,
    route,
    movement,
    propGroundAnchors,
    durationMs,
    terrain,
    characterAt,
    sample,
    poseAt: (tMs) => {
      const s = sample(tMs);
      return { layers: s.layers, rootTransform: s.rootTransform };
    },
  };
}
