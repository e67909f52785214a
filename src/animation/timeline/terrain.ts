import { fail, isArrayLike, requireVec } from '../../errors/validate.ts';
import type { Vec3 } from '../model/model-types.ts';

/** Ground height under a horizontal position, in metres. */
export type TerrainHeight = (x: number, z: number) => number;

/** Flat ground at y = 0, the default terrain. */
export const flatTerrain: TerrainHeight = () => 0;

export function groundHeight(terrain: TerrainHeight, x: number, z: number, field = 'terrain'): number {
  const y = terrain(x, z);
  if (typeof y !== 'number' || !Number.isFinite(y)) fail('INVALID_OPTION', field, `terrain height at (${x}, ${z}) is not finite (${String(y)})`);
  return y;
}

export interface PropInput {
  kind: string;
  position: readonly number[];
}

/** A prop standing on the terrain: its xz as given, its y the ground height there. */
export interface PropGroundAnchor {
  readonly kind: string;
  readonly position: Vec3;
  readonly groundY: number;
}

/** Validates `props` and grounds each on the terrain (`propGroundAnchors` in snapshots). */
export function groundProps(props: unknown, terrain: TerrainHeight, field = 'props'): PropGroundAnchor[] {
  if (props === undefined) return [];
  if (!isArrayLike(props)) fail('INVALID_OPTION', field, 'expected an array of props');
  return Array.from(props as ArrayLike<unknown>, (raw, i) => {
    if (typeof raw !== 'object' || raw === null) fail('INVALID_OPTION', `${field}[${i}]`, 'expected { kind, position }');
    const prop = raw as PropInput;
    if (typeof prop.kind !== 'string' || prop.kind === '') fail('INVALID_OPTION', `${field}[${i}].kind`, 'expected a non-empty string');
    const [x, , z] = requireVec(prop.position, 3, `${field}[${i}].position`);
    const groundY = groundHeight(terrain, x, z);
    return { kind: prop.kind, position: [x, groundY, z], groundY };
  });
}
