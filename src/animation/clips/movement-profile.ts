import { fail, requireFiniteNumber } from '../../errors/validate.ts';

/** How a clip moves the character (host metadata: the 0.2 API's `movementProfile`). */
export interface ClipMovementProfileInput {
  /**
   * 'authored': the clip's root joint translates (a walk that walks forward); 'in-place': it does
   * not. Default 'in-place'.
   */
  rootMotion?: 'authored' | 'in-place';
  /** Declared horizontal travel per clip loop in metres; default: measured from the root channel. */
  distancePerLoop?: number;
  /** Lets a stationary beat keep the clip's authored root translation; default false. */
  allowsRootTranslation?: boolean;
  /** Name of the root-motion node; default: the top-most joint of the first skin. */
  rootNode?: string;
}

export interface ClipMovementProfile {
  readonly rootMotion: 'authored' | 'in-place';
  readonly declaredDistancePerLoop: number | null;
  readonly allowsRootTranslation: boolean;
  readonly rootNode: string | null;
}

export function validateMovementProfile(input: unknown, field: string): ClipMovementProfile {
  if (typeof input !== 'object' || input === null) fail('INVALID_OPTION', field, 'expected a movement profile object');
  const profile = input as ClipMovementProfileInput;
  const rootMotion = profile.rootMotion ?? 'in-place';
  if (rootMotion !== 'authored' && rootMotion !== 'in-place') fail('INVALID_OPTION', `${field}.rootMotion`, `expected 'authored' or 'in-place', got ${JSON.stringify(rootMotion)}`);
  let declared: number | null = null;
  if (profile.distancePerLoop !== undefined) {
    declared = requireFiniteNumber(profile.distancePerLoop, `${field}.distancePerLoop`);
    if (declared < 0) fail('INVALID_OPTION', `${field}.distancePerLoop`, `must be >= 0, got ${declared}`);
  }
  const allows = profile.allowsRootTranslation ?? false;
  if (typeof allows !== 'boolean') fail('INVALID_OPTION', `${field}.allowsRootTranslation`, 'expected a boolean');
  const rootNode = profile.rootNode ?? null;
  if (rootNode !== null && (typeof rootNode !== 'string' || rootNode === '')) fail('INVALID_OPTION', `${field}.rootNode`, 'expected a node name');
  return { rootMotion, declaredDistancePerLoop: declared, allowsRootTranslation: allows, rootNode };
}
