import { fail, isArrayLike, requireFiniteNumber } from '../../errors/validate.ts';
import type { ClipLibrary, LibraryClip } from '../clips/clip-library.ts';

export type MovementKind = 'stationary' | 'travel' | 'jump';

/** What a beat must do to the character's position. */
export interface MovementRequirementInput {
  kind: MovementKind;
  /** Travel/jump: the distance the beat should cover, in metres (also its cap). Default: up to the next route anchor. */
  distance?: number;
}

export interface AnimationBeatInput {
  id: string;
  /** Beats play in ascending `order` (ties keep array order). */
  order: number;
  clipId: string;
  durationMs: number;
  /** Cross-fade into this beat (`inMs`) and out of it (`outMs`); default 0. */
  blend?: { inMs?: number; outMs?: number };
  movementRequirement?: MovementRequirementInput;
}

export interface AnimationBeat {
  readonly id: string;
  readonly order: number;
  readonly clip: LibraryClip;
  readonly durationMs: number;
  readonly blendInMs: number;
  readonly blendOutMs: number;
  readonly requirement: { readonly kind: MovementKind; readonly distance: number | null } | null;
  /** Start on the scene clock: the sum of the durations of the beats before it. */
  readonly startMs: number;
  readonly endMs: number;
  /** Index of the input entry (for error fields and diagnostics). */
  readonly inputIndex: number;
}

function nonNegative(value: unknown, field: string): number {
  const n = requireFiniteNumber(value, field);
  if (n < 0) fail('INVALID_OPTION', field, `must be >= 0, got ${n}`);
  return n;
}

/**
 * Validates `beats` and lays them out back to back in `order`. Every beat needs a unique id, a
 * clip the library has, a positive duration, blends that fit in it (inMs + outMs <= durationMs, so
 * cross-fades of neighbouring boundaries never overlap) and, optionally, a movement requirement.
 */
export function scheduleBeats(beats: unknown, library: ClipLibrary, field = 'beats'): AnimationBeat[] {
  if (!isArrayLike(beats) || beats.length === 0) fail('INVALID_OPTION', field, 'expected a non-empty array of beats');
  const ids = new Set<string>();
  const parsed = Array.from(beats as ArrayLike<unknown>, (raw, i) => {
    const f = `${field}[${i}]`;
    if (typeof raw !== 'object' || raw === null) fail('INVALID_OPTION', f, 'expected a beat object');
    const beat = raw as AnimationBeatInput;
    if (typeof beat.id !== 'string' || beat.id === '') fail('INVALID_OPTION', `${f}.id`, 'expected a non-empty string');
    if (ids.has(beat.id)) fail('INVALID_OPTION', `${f}.id`, `duplicate beat id ${JSON.stringify(beat.id)}`);
    ids.add(beat.id);
    const order = requireFiniteNumber(beat.order, `${f}.order`);
    if (typeof beat.clipId !== 'string') fail('INVALID_OPTION', `${f}.clipId`, 'expected a clip id');
    const clip = library.clips.get(beat.clipId);
    if (clip === undefined) {
      fail('INVALID_OPTION', `${f}.clipId`, `unknown clip ${JSON.stringify(beat.clipId)} (have ${[...library.clips.keys()].map((k) => JSON.stringify(k)).join(', ') || 'none'})`);
    }
    const durationMs = requireFiniteNumber(beat.durationMs, `${f}.durationMs`);
    if (!(durationMs > 0)) fail('INVALID_OPTION', `${f}.durationMs`, `must be > 0, got ${durationMs}`);
    const blend = beat.blend ?? {};
    if (typeof blend !== 'object' || blend === null) fail('INVALID_OPTION', `${f}.blend`, 'expected { inMs, outMs }');
    const blendInMs = blend.inMs === undefined ? 0 : nonNegative(blend.inMs, `${f}.blend.inMs`);
    const blendOutMs = blend.outMs === undefined ? 0 : nonNegative(blend.outMs, `${f}.blend.outMs`);
    if (blendInMs + blendOutMs > durationMs) fail('INVALID_OPTION', `${f}.blend`, `inMs + outMs (${blendInMs + blendOutMs}) exceeds durationMs (${durationMs})`);
    let requirement: AnimationBeat['requirement'] = null;
    if (beat.movementRequirement !== undefined) {
      const r = beat.movementRequirement;
      if (typeof r !== 'object' || r === null) fail('INVALID_OPTION', `${f}.movementRequirement`, 'expected { kind, distance? }');
      if (r.kind !== 'stationary' && r.kind !== 'travel' && r.kind !== 'jump') {
        fail('INVALID_OPTION', `${f}.movementRequirement.kind`, `expected 'stationary', 'travel' or 'jump', got ${JSON.stringify(r.kind)}`);
      }
      const distance = r.distance === undefined ? null : nonNegative(r.distance, `${f}.movementRequirement.distance`);
      requirement = { kind: r.kind, distance };
    }
    return { id: beat.id, order, clip, durationMs, blendInMs, blendOutMs, requirement, inputIndex: i };
  });
  parsed.sort((a, b) => a.order - b.order || a.inputIndex - b.inputIndex);
  let startMs = 0;
  return parsed.map((beat) => {
    const scheduled = { ...beat, startMs, endMs: startMs + beat.durationMs };
    startMs += beat.durationMs;
    return scheduled;
  });
}
