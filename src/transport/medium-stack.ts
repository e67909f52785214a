import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { requireInteger } from '../errors/validate.ts';
import { MEDIUM_STACK_DEPTH } from '../gpu-layout/constants.ts';

/**
 * Nested participating media along one ray, innermost last. The GPU path state carries a bounded
 * stack (`MEDIUM_STACK_DEPTH` ids in PathState.media), so this reference implementation enforces the same bound and
 * reports, instead of hiding, the two ways a scene can violate it: entering a fifth medium
 * (overflow) and leaving a medium that is not the innermost one (mismatch, e.g. overlapping or
 * non-closed volumes; pbrt-v4 "Media" section discusses the same ambiguity for medium interfaces).
 */
export const mediumStackLimit = MEDIUM_STACK_DEPTH;

/** Medium id 0 means "no medium" (vacuum / the scene's outer medium), as PathState.mediumId does. */
export const noMediumId = 0;

export interface MediumStack {
  /** Medium ids, outermost first, innermost last. */
  readonly media: readonly number[];
  readonly depth: number;
  readonly capacity: number;
  /** Innermost medium id, or 0 when the stack is empty. */
  readonly current: number;
  /** Whether `id` is anywhere on the stack. */
  contains(id: number): boolean;
  /** The stack after the ray crosses into medium `id`. */
  enter(id: number): MediumStackTransition;
  /** The stack after the ray leaves medium `id`. */
  exit(id: number): MediumStackTransition;
}

export interface MediumStackTransition {
  readonly stack: MediumStack;
  /** Entering would exceed `mediumStackLimit`: the stack is left unchanged. */
  readonly overflow: boolean;
  /** The exited medium was not the innermost one (it is removed if present, else nothing changes). */
  readonly mismatch: boolean;
}

function validateId(id: unknown, field: string): number {
  const value = requireInteger(id, field, { min: 1, max: 0xffffffff });
  return value;
}

function build(media: readonly number[]): MediumStack {
  const frozen = Object.freeze([...media]);
  const stack: MediumStack = {
    media: frozen,
    depth: frozen.length,
    capacity: mediumStackLimit,
    current: frozen.length > 0 ? frozen[frozen.length - 1]! : noMediumId,
    contains: (id) => frozen.includes(id),
    enter(id) {
      const value = validateId(id, 'mediumId');
      if (frozen.length >= mediumStackLimit) return Object.freeze({ stack, overflow: true, mismatch: false });
      return Object.freeze({ stack: build([...frozen, value]), overflow: false, mismatch: false });
    },
    exit(id) {
      const value = validateId(id, 'mediumId');
      const at = frozen.lastIndexOf(value);
      if (at < 0) return Object.freeze({ stack, overflow: false, mismatch: true });
      const rest = frozen.filter((_, i) => i !== at);
      return Object.freeze({ stack: build(rest), overflow: false, mismatch: at !== frozen.length - 1 });
    },
  };
  return Object.freeze(stack);
}

/** An immutable medium stack holding `ids` (outermost first); at most `mediumStackLimit` of them. */
export function createMediumStack(ids: readonly number[] = []): MediumStack {
  if (!Array.isArray(ids)) throw new GpuRendererError('INVALID_OPTION', 'expected an array of medium ids', { field: 'ids' });
  if (ids.length > mediumStackLimit) {
    throw new GpuRendererError('INVALID_OPTION', `at most ${mediumStackLimit} nested media are supported, got ${ids.length}`, { field: 'ids' });
  }
  return build(ids.map((id, i) => validateId(id, `ids[${i}]`)));
}

export function isMediumStack(value: unknown): value is MediumStack {
  return (
    typeof value === 'object' &&
    value !== null &&
    Array.isArray((value as MediumStack).media) &&
    typeof (value as MediumStack).enter === 'function' &&
    typeof (value as MediumStack).exit === 'function'
  );
}
