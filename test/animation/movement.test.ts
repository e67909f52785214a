import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createSceneTimeline } from '../../src/animation/timeline/scene-timeline.ts';
import type { MovementDiagnosticCode } from '../../src/animation/timeline/movement.ts';
import { createFigureSetup } from './fixtures/figure-library.ts';
import { WALK_DISTANCE_PER_LOOP, WALK_DURATION_S } from './fixtures/rigged-figure.ts';
import { assertClose, assertNear } from './helpers.ts';

const setup = createFigureSetup();
const codes = (diagnostics: readonly { code: MovementDiagnosticCode }[]): MovementDiagnosticCode[] => diagnostics.map((d) => d.code).sort();

test('the measured walk travel per loop accounts for the 0.5-scaled armature', () => {
  const walk = setup.library.clips.get('walk')!;
  assertNear(walk.measuredDistancePerLoop, WALK_DISTANCE_PER_LOOP, 1e-6, 'walk');
  assert.equal(walk.distancePerLoop, walk.measuredDistancePerLoop);
  assertNear(setup.library.clips.get('idle')!.measuredDistancePerLoop, 0, 1e-9, 'idle');
  assert.equal(setup.library.clips.get('walk-declared-1.5')!.distancePerLoop, 1.5);
});

test('repeated travel beats accumulate loops x distance per loop, capped by the segment and the requirement', () => {
  const route = [
    { position: [0, 0, 0], arriveMs: 0 },
    { position: [0, 0, 4], arriveMs: 5000 },
    { position: [3, 0, 4], arriveMs: 8000 },
  ];
  const beats = [
    { id: 'go-1', order: 1, clipId: 'walk', durationMs: 2500, movementRequirement: { kind: 'travel' } },
    { id: 'go-2', order: 2, clipId: 'walk', durationMs: 2500, movementRequirement: { kind: 'travel' } },
    { id: 'rest', order: 3, clipId: 'idle', durationMs: 1000, movementRequirement: { kind: 'stationary' } },
    { id: 'go-3', order: 4, clipId: 'walk', durationMs: 3000, movementRequirement: { kind: 'travel', distance: 2 } },
  ];
  const timeline = createSceneTimeline(setup.library, { beats, route });
  const plan = timeline.movement;
  assert.equal(plan.mode, 'per-beat');
  const speed = WALK_DISTANCE_PER_LOOP / (WALK_DURATION_S * 1000);
  // go-1: 2.5 loops of 1 m on a 4 m segment: 2.5 m, uncapped.
  assertNear(plan.beats[0].endDistance - plan.beats[0].startDistance, (2500 / 1000) * WALK_DISTANCE_PER_LOOP, 1e-9, 'go-1');
  // go-2: another 2.5 m of root motion, but only 1.5 m of the segment is left.
  assertNear(plan.beats[1].endDistance - plan.beats[1].startDistance, 4 - 2.5, 1e-9, 'go-2 capped by the segment');
  assertNear(plan.beats[1].moveEndMs, 2500 + 1.5 / speed, 1e-9, 'go-2 stops when the anchor is reached');
  assertNear(plan.beats[2].endDistance - plan.beats[2].startDistance, 0, 0, 'rest holds');
  // go-3: 3 loops = 3 m of root motion, the requirement caps it at 2 m.
  assertNear(plan.beats[3].endDistance - plan.beats[3].startDistance, 2, 1e-9, 'go-3 capped by the requirement');
  for (const [t, expected] of [[1250, [0, 0, 1.25]], [3750, [0, 0, 3.75]], [4500, [0, 0, 4]], [5500, [0, 0, 4]], [6500, [0.5, 0, 4]], [9000, [2, 0, 4]], [20000, [2, 0, 4]]] as const) {
    assertClose(timeline.characterAt(t).position, expected, 1e-9, `position at ${t} ms`);
  }
  assertNear(timeline.characterAt(1000).yaw, 0, 1e-12, 'facing +Z on the first leg');
  assertNear(timeline.characterAt(6500).yaw, Math.PI / 2, 1e-12, 'facing +X on the second leg');
  assertClose(timeline.characterAt(1000).velocity, [0, 0, speed * 1000], 1e-9, 'velocity m/s while walking');
  assertClose(timeline.characterAt(5500).velocity, [0, 0, 0], 0, 'no velocity while resting');
  assert.deepEqual(codes(plan.diagnostics), ['arrival-time-mismatch', 'root-motion-capped', 'root-motion-capped', 'route-incomplete']);
  const arrival = plan.diagnostics.find((d) => d.code === 'arrival-time-mismatch')!;
  assert.equal(arrival.routeIndex, 1);
  assertNear(arrival.actual!, 4000, 1e-9, 'anchor 1 reached after 4 m at 1 m/s');
  const incomplete = plan.diagnostics.find((d) => d.code === 'route-incomplete')!;
  assertNear(incomplete.actual!, 6, 1e-9, 'reached distance');
  assert.equal(incomplete.expected, 7);
  assert.equal(plan.beats[0].rootMotion, 'in-place', 'the route moves the character, so the clip root is made in-place');
});

test('a schedule that fits produces no diagnostics', () => {
  const route = [{ position: [0, 0, 0], arriveMs: 0 }, { position: [0, 0, 3], arriveMs: 3000 }];
  const beats = [
    { id: 'walk', order: 0, clipId: 'walk', durationMs: 3000, movementRequirement: { kind: 'travel', distance: 3 } },
    { id: 'idle', order: 1, clipId: 'idle', durationMs: 2000, movementRequirement: { kind: 'stationary' } },
  ];
  const timeline = createSceneTimeline(setup.library, { beats, route });
  assert.deepEqual(timeline.movement.diagnostics, []);
  assert.deepEqual(timeline.movement.anchorArrivalsMs, [0, 3000]);
});

test('mismatches are diagnosed: no root motion on travel, locked stationary root motion, wrong declared distance, exhausted route, short requirement', () => {
  const route = [{ position: [0, 0, 0], arriveMs: 0 }, { position: [2, 0, 0], arriveMs: 4000 }];
  const beats = [
    { id: 'slide', order: 0, clipId: 'idle', durationMs: 2000, movementRequirement: { kind: 'travel', distance: 1 } },
    { id: 'march-on-spot', order: 1, clipId: 'walk', durationMs: 1000, movementRequirement: { kind: 'stationary' } },
    { id: 'strut', order: 2, clipId: 'walk-in-place-allowed', durationMs: 1000, movementRequirement: { kind: 'stationary' } },
    { id: 'hop', order: 3, clipId: 'walk-declared-1.5', durationMs: 500, movementRequirement: { kind: 'jump', distance: 1 } },
    { id: 'beyond', order: 4, clipId: 'walk', durationMs: 1000, movementRequirement: { kind: 'travel' } },
  ];
  const timeline = createSceneTimeline(setup.library, { beats, route });
  const plan = timeline.movement;
  const byBeat = (id: string): string[] => plan.diagnostics.filter((d) => d.beatId === id).map((d) => d.code);
  assert.deepEqual(byBeat('slide'), ['travel-without-root-motion']);
  assertNear(plan.beats[0].endDistance, 1, 1e-12, 'a travel beat without root motion still covers its required distance');
  assertClose(timeline.characterAt(1000).position, [0.5, 0, 0], 1e-12, 'evenly over the beat');
  assert.deepEqual(byBeat('march-on-spot'), ['stationary-root-motion-locked']);
  assert.equal(plan.beats[1].rootMotion, 'in-place');
  assert.deepEqual(byBeat('strut'), []);
  assert.equal(plan.beats[2].rootMotion, 'authored', 'allowsRootTranslation keeps the authored root translation');
  // hop: declared 1.5 m per 1 s loop, 0.5 s long: 0.75 m < required 1 m.
  assert.deepEqual(byBeat('hop'), ['insufficient-root-motion']);
  assertNear(plan.beats[3].endDistance - plan.beats[3].startDistance, 0.75, 1e-9, 'hop distance from the declared profile');
  assert.ok(plan.diagnostics.some((d) => d.code === 'profile-distance-mismatch' && d.clipId === 'walk-declared-1.5' && d.expected === 1.5));
  // beyond: 1 m of walking reaches the anchor at 2 m, nothing is left after it.
  const anotherBeat = [...beats, { id: 'past-the-end', order: 5, clipId: 'walk', durationMs: 500, movementRequirement: { kind: 'travel' } }];
  const exhausted = createSceneTimeline(setup.library, { beats: anotherBeat, route }).movement;
  assert.deepEqual(exhausted.diagnostics.filter((d) => d.beatId === 'past-the-end').map((d) => d.code), ['route-exhausted']);
});

test('without movement requirements the route arrival times drive the character (route-timed)', () => {
  const route = [{ position: [0, 0, 0], arriveMs: 0 }, { position: [0, 0, 2], arriveMs: 1000 }, { position: [-2, 0, 2], arriveMs: 3000 }];
  const beats = [{ id: 'a', order: 0, clipId: 'walk', durationMs: 4000 }];
  const timeline = createSceneTimeline(setup.library, { beats, route });
  assert.equal(timeline.movement.mode, 'route-timed');
  assertClose(timeline.characterAt(500).position, [0, 0, 1], 1e-12);
  assertClose(timeline.characterAt(2000).position, [-1, 0, 2], 1e-12);
  assertClose(timeline.characterAt(3500).position, [-2, 0, 2], 1e-12);
  assertNear(timeline.characterAt(2000).yaw, -Math.PI / 2, 1e-12, 'facing -X');
  assertClose(timeline.characterAt(2000).velocity, [-1, 0, 0], 1e-12, '2 m in 2 s');
  assert.equal(timeline.movement.beats[0].rootMotion, 'in-place', 'authored root motion is removed when the route moves the character');
  assert.equal(timeline.movement.beats[0].kind, 'travel');
});

test('the character and props stand on the terrain; route points off the ground are diagnosed', () => {
  const terrain = (x: number, z: number): number => 0.1 * x + 0.05 * z * z;
  const route = [{ position: [0, 0, 0], arriveMs: 0 }, { position: [2, 0, 2], arriveMs: 2000 }];
  const props = [{ kind: 'crate', position: [1, 99, -1] }, { kind: 'lamp', position: [-2, 0, 3] }];
  const timeline = createSceneTimeline(setup.library, { beats: [{ id: 'a', order: 0, clipId: 'idle', durationMs: 2000 }], route, props, terrain });
  const at = timeline.characterAt(1000);
  assertClose(at.position, [1, terrain(1, 1), 1], 1e-12, 'character grounded');
  assert.equal(at.groundY, terrain(1, 1));
  assert.deepEqual(timeline.propGroundAnchors.map((p) => p.kind), ['crate', 'lamp']);
  assertClose(timeline.propGroundAnchors[0].position, [1, terrain(1, -1), -1], 1e-12, 'crate on the ground');
  assertClose(timeline.propGroundAnchors[1].position, [-2, terrain(-2, 3), 3], 1e-12, 'lamp on the ground');
  const offGround = timeline.movement.diagnostics.filter((d) => d.code === 'route-point-off-ground');
  assert.deepEqual(offGround.map((d) => d.routeIndex), [1], 'route point 1 is at y 0, the ground there is at 0.4');
});
