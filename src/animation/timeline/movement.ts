import type { LibraryClip } from '../clips/clip-library.ts';
import type { AnimationBeat, MovementKind } from './beats.ts';
import { routeDistanceAtTime, type Route } from './route.ts';
import { groundHeight, type TerrainHeight } from './terrain.ts';

export type MovementDiagnosticCode =
  /** A travel/jump beat plays a clip without authored root motion: the route slides the character. */
  | 'travel-without-root-motion'
  /** The clip's root motion over the beat falls short of the beat's required distance. */
  | 'insufficient-root-motion'
  /** The clip's root motion over the beat exceeds the requirement or the route segment; the character stops at the cap. */
  | 'root-motion-capped'
  /** A stationary beat plays a clip with authored root motion that the profile does not allow: translation removed. */
  | 'stationary-root-motion-locked'
  /** A profile's declared distance per loop differs from the one measured from the clip's root keyframes. */
  | 'profile-distance-mismatch'
  /** A travel/jump beat comes after the last route anchor. */
  | 'route-exhausted'
  /** The beats end before the character reaches the last route anchor. */
  | 'route-incomplete'
  /** An anchor is reached at a time other than its `arriveMs`. */
  | 'arrival-time-mismatch'
  /** A route point's height differs from the terrain under it. */
  | 'route-point-off-ground';

export interface MovementDiagnostic {
  readonly code: MovementDiagnosticCode;
  readonly message: string;
  readonly beatId?: string;
  readonly clipId?: string;
  readonly routeIndex?: number;
  readonly expected?: number;
  readonly actual?: number;
}

/** How one beat moves the character along the route (arc lengths in metres, times in ms). */
export interface BeatMovement {
  readonly beatId: string;
  readonly kind: MovementKind;
  readonly startMs: number;
  readonly endMs: number;
  readonly startDistance: number;
  readonly endDistance: number;
  /** Metres per millisecond while moving. */
  readonly speed: number;
  /** When the movement stops (<= endMs; earlier when capped). */
  readonly moveEndMs: number;
  /** 'in-place' strips the clip's horizontal root travel because the route moves the character. */
  readonly rootMotion: 'authored' | 'in-place';
}

export interface MovementPlan {
  /** 'per-beat' when any beat has a movementRequirement, else 'route-timed' (position from arriveMs). */
  readonly mode: 'per-beat' | 'route-timed';
  readonly beats: readonly BeatMovement[];
  /** Time each route anchor is reached (null: never). */
  readonly anchorArrivalsMs: readonly (number | null)[];
  readonly diagnostics: readonly MovementDiagnostic[];
}

export interface MovementTolerances {
  /** Metres; default 0.05. */
  distanceM?: number;
  /** Milliseconds; default 250. */
  arrivalMs?: number;
}

function isAuthored(clip: LibraryClip): boolean {
  return clip.profile?.rootMotion === 'authored';
}

const fmt = (x: number): string => (Math.round(x * 1000) / 1000).toString();

/**
 * Resolves the character's displacement beat by beat (the 0.2 API's movement rules, which its hosts rely on):
 * - travel and jump beats move from the current route anchor towards the next one. With an
 *   authored-root-motion clip they move at the clip's speed (distance per loop / clip duration),
 *   so over a beat the distance is loops x distance per loop with loops = durationMs / clip
 *   duration, capped by the requirement's distance and by the end of the route segment; repeated
 *   travel beats accumulate along the same segment until its anchor is reached. Without root
 *   motion they cover the rest of the segment (or the required distance) evenly over the beat.
 * - stationary beats hold the current position; the clip's root translation is removed unless
 *   its profile allows authored root translation.
 * Without any movementRequirement the route's arrival times drive the position ('route-timed').
 */
export function resolveMovement(beats: readonly AnimationBeat[], route: Route, terrain: TerrainHeight, tolerances: MovementTolerances = {}): MovementPlan {
  const tol = tolerances.distanceM ?? 0.05;
  const arrivalTol = tolerances.arrivalMs ?? 250;
  const diagnostics: MovementDiagnostic[] = [];
  const n = route.points.length;
  route.points.forEach((point, i) => {
    const ground = groundHeight(terrain, point.position[0], point.position[2]);
    if (Math.abs(point.position[1] - ground) > tol) {
      diagnostics.push({ code: 'route-point-off-ground', routeIndex: i, expected: ground, actual: point.position[1], message: `route point ${i} is at y ${fmt(point.position[1])}, the ground there is at ${fmt(ground)}` });
    }
  });
  const checkedClips = new Set<string>();
  for (const beat of beats) {
    const clip = beat.clip;
    if (checkedClips.has(clip.id)) continue;
    checkedClips.add(clip.id);
    const declared = clip.profile?.declaredDistancePerLoop ?? null;
    if (declared !== null && Math.abs(declared - clip.measuredDistancePerLoop) > tol) {
      diagnostics.push({ code: 'profile-distance-mismatch', clipId: clip.id, expected: declared, actual: clip.measuredDistancePerLoop, message: `clip ${clip.id} declares ${fmt(declared)} m per loop, its root keyframes travel ${fmt(clip.measuredDistancePerLoop)} m` });
    }
  }

  if (!beats.some((beat) => beat.requirement !== null)) {
    return {
      mode: 'route-timed',
      beats: beats.map((beat) => {
        const startDistance = routeDistanceAtTime(route, beat.startMs);
        const endDistance = routeDistanceAtTime(route, beat.endMs);
        // Descriptive only: in this mode the route schedule, not the beat, moves the character (speed via movementSpeedAt).
        const kind: MovementKind = endDistance > startDistance ? 'travel' : 'stationary';
        return { beatId: beat.id, kind, startMs: beat.startMs, endMs: beat.endMs, startDistance, endDistance, speed: 0, moveEndMs: beat.endMs, rootMotion: isAuthored(beat.clip) ? 'in-place' : 'authored' };
      }),
      anchorArrivalsMs: route.points.map((p) => p.arriveMs),
      diagnostics,
    };
  }

  const arrivals: (number | null)[] = new Array<number | null>(n).fill(null);
  arrivals[0] = 0;
  let segment = 0;
  let progress = 0;
  const segmentLength = (k: number): number => route.cumulative[k + 1] - route.cumulative[k];
  const skipEmptySegments = (timeMs: number): void => {
    while (segment < n - 1 && segmentLength(segment) - progress <= 1e-9) {
      segment++;
      progress = 0;
      arrivals[segment] = timeMs;
    }
  };
  skipEmptySegments(0);
  const plan: BeatMovement[] = [];
  for (const beat of beats) {
    const kind = beat.requirement?.kind ?? 'stationary';
    const clip = beat.clip;
    const authored = isAuthored(clip);
    const startDistance = route.cumulative[segment] + progress;
    const hold = (rootMotion: 'authored' | 'in-place'): void => {
      plan.push({ beatId: beat.id, kind, startMs: beat.startMs, endMs: beat.endMs, startDistance, endDistance: startDistance, speed: 0, moveEndMs: beat.startMs, rootMotion });
    };
    if (kind === 'stationary') {
      const locked = authored && !(clip.profile?.allowsRootTranslation ?? false);
      if (locked && clip.distancePerLoop > tol) {
        diagnostics.push({ code: 'stationary-root-motion-locked', beatId: beat.id, clipId: clip.id, expected: 0, actual: clip.distancePerLoop, message: `stationary beat ${beat.id} plays ${clip.id}, which travels ${fmt(clip.distancePerLoop)} m per loop; its root translation is removed` });
      }
      hold(locked ? 'in-place' : 'authored');
      continue;
    }
    if (segment >= n - 1) {
      diagnostics.push({ code: 'route-exhausted', beatId: beat.id, clipId: clip.id, message: `${kind} beat ${beat.id} starts at the last route anchor; there is nowhere left to go` });
      hold(authored ? 'in-place' : 'authored');
      continue;
    }
    const remaining = segmentLength(segment) - progress;
    const required = beat.requirement?.distance ?? null;
    const cap = Math.min(required ?? Infinity, remaining);
    let covered: number;
    let speed: number;
    let moveEndMs: number;
    if (authored && clip.distancePerLoop > tol) {
      speed = clip.distancePerLoop / clip.durationMs;
      const uncapped = speed * beat.durationMs;
      covered = Math.min(uncapped, cap);
      moveEndMs = beat.startMs + covered / speed;
      if (required !== null && uncapped < required - tol) {
        diagnostics.push({ code: 'insufficient-root-motion', beatId: beat.id, clipId: clip.id, expected: required, actual: uncapped, message: `beat ${beat.id} requires ${fmt(required)} m, ${clip.id}'s root motion covers ${fmt(uncapped)} m in ${beat.durationMs} ms` });
      }
      if (uncapped > cap + tol) {
        diagnostics.push({ code: 'root-motion-capped', beatId: beat.id, clipId: clip.id, expected: cap, actual: uncapped, message: `beat ${beat.id}: ${clip.id}'s root motion covers ${fmt(uncapped)} m, capped at ${fmt(cap)} m by the ${required !== null && required <= remaining ? 'requirement' : 'route segment'}` });
      }
    } else {
      diagnostics.push({ code: 'travel-without-root-motion', beatId: beat.id, clipId: clip.id, message: `${kind} beat ${beat.id} plays ${clip.id}, which has no authored root motion; the character slides along the route` });
      covered = cap;
      speed = covered / beat.durationMs;
      moveEndMs = beat.endMs;
    }
    progress += covered;
    plan.push({ beatId: beat.id, kind, startMs: beat.startMs, endMs: beat.endMs, startDistance, endDistance: startDistance + covered, speed, moveEndMs, rootMotion: authored ? 'in-place' : 'authored' });
    skipEmptySegments(moveEndMs);
  }
  if (segment < n - 1) {
    const reached = route.cumulative[segment] + progress;
    diagnostics.push({ code: 'route-incomplete', expected: route.length, actual: reached, routeIndex: segment + 1, message: `the beats end ${fmt(route.length - reached)} m before the last route anchor` });
  }
  arrivals.forEach((time, i) => {
    if (i === 0 || time === null) return;
    const expected = route.points[i].arriveMs;
    if (Math.abs(time - expected) > arrivalTol) {
      diagnostics.push({ code: 'arrival-time-mismatch', routeIndex: i, expected, actual: time, message: `route anchor ${i} is reached at ${fmt(time)} ms, expected at ${fmt(expected)} ms` });
    }
  });
  return { mode: 'per-beat', beats: plan, anchorArrivalsMs: arrivals, diagnostics };
}

/** Route arc length at `tMs` under a movement plan. */
export function movementDistanceAt(plan: MovementPlan, route: Route, tMs: number): number {
  if (plan.mode === 'route-timed') return routeDistanceAtTime(route, tMs);
  const beat = plan.beats.findLast((b) => b.startMs <= tMs) ?? plan.beats[0];
  const moving = Math.min(Math.max(tMs, beat.startMs), beat.moveEndMs) - beat.startMs;
  return beat.startDistance + beat.speed * moving;
}

/** Speed along the route at `tMs`, metres per millisecond (0 when holding). */
export function movementSpeedAt(plan: MovementPlan, route: Route, tMs: number): number {
  if (plan.mode === 'route-timed') {
    const points = route.points;
    for (let i = 1; i < points.length; i++) {
      if (tMs >= points[i - 1].arriveMs && tMs < points[i].arriveMs) return (route.cumulative[i] - route.cumulative[i - 1]) / (points[i].arriveMs - points[i - 1].arriveMs);
    }
    return 0;
  }
  const beat = plan.beats.findLast((b) => b.startMs <= tMs);
  return beat !== undefined && tMs < beat.moveEndMs ? beat.speed : 0;
}
