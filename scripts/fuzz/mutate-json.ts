/**
 * Structure-aware mutation of JSON documents (glTF, scene files, option sets): a random node is
 * replaced by a boundary value, deleted, duplicated, wrapped, or gains a key; numbers are nudged
 * across the boundaries loaders check (ranges, integer limits, float32 and the renderer's 1e18).
 */
import type { Random } from './random.ts';

export type Json = null | boolean | number | string | Json[] | { [key: string]: Json };
export type JsonPath = Array<string | number>;

const LONG = 'x'.repeat(10_000);

/** Values at the edges of what loaders accept. */
export const BOUNDARY_VALUES: readonly Json[] = [
  0, -0, 1, -1, 2, 3, 4, 0.5, 1.5, -0.5, 255, 256, 65535, 65536, 2 ** 31 - 1, 2 ** 31, 2 ** 32 - 1, 2 ** 32, 2 ** 32 + 1, 2 ** 53, -(2 ** 31),
  1e18, 1e19, -1e19, 3.4e38, 3.5e38, 1e300, -1e300, 5e-324, 1e-30, Math.PI, 3.1416, 1e20, 1e21,
  5120, 5121, 5122, 5123, 5125, 5126, 5130, 5131, 9728, 9729, 9987, 10497, 33071, 33648, 34962, 34963,
  '', 'x', LONG, '1', '1.5', 'NaN', 'SCALAR', 'VEC2', 'VEC3', 'VEC4', 'MAT2', 'MAT3', 'MAT4', 'OPAQUE', 'MASK', 'BLEND', 'perspective', 'orthographic',
  'point', 'spot', 'directional', 'LINEAR', 'STEP', 'CUBICSPLINE', 'translation', 'weights', 'image/png', 'image/jpeg', 'image/ktx2', '__proto__', 'constructor',
  null, true, false, [], {}, [1, 2, 3], [0, 0, 0, 0], [2, 2, 2], [1, 1, 1, 1], [-1, 0, 0], [1e19, 0, 0], [[1]], { index: 0 }, { a: 1 },
  // A key named __proto__ (as JSON.parse makes it): loaders must not pollute Object.prototype.
  JSON.parse('{"__proto__": {"polluted": true}}') as Json,
];

function nudge(value: number, random: Random): number {
  return random.pick([
    value + 1, value - 1, -value, value * 2, value / 2, value * 1e10, value * 1e20, value + 0.5, Math.round(value) + 2 ** 31, value * 255, 1 - value, value + 1e-7,
  ]);
}

/** Every path in `value`, depth-first (the root is []); `limit` bounds the walk. */
export function jsonPaths(value: Json, limit = 20_000): JsonPath[] {
  const out: JsonPath[] = [];
  const stack: Array<{ v: Json; path: JsonPath }> = [{ v: value, path: [] }];
  while (stack.length > 0 && out.length < limit) {
    const { v, path } = stack.pop()!;
    out.push(path);
    if (Array.isArray(v)) v.forEach((x, i) => stack.push({ v: x, path: [...path, i] }));
    else if (v !== null && typeof v === 'object') for (const [k, x] of Object.entries(v)) stack.push({ v: x, path: [...path, k] });
  }
  return out;
}

export function getAt(value: Json, path: JsonPath): Json {
  let v: Json = value;
  for (const k of path) v = (v as Record<string | number, Json>)[k as string]!;
  return v;
}

/** A copy of `value` with `path` set to `replacement` (`undefined` deletes it). */
export function setAt(value: Json, path: JsonPath, replacement: Json | undefined): Json {
  if (path.length === 0) return replacement === undefined ? null : replacement;
  const [head, ...rest] = path;
  if (Array.isArray(value)) {
    const copy = [...value];
    if (rest.length === 0 && replacement === undefined) copy.splice(head as number, 1);
    else copy[head as number] = setAt(copy[head as number]!, rest, replacement) as Json;
    return copy;
  }
  const copy = { ...(value as Record<string, Json>) };
  if (rest.length === 0 && replacement === undefined) delete copy[head as string];
  else copy[head as string] = setAt(copy[head as string]!, rest, replacement) as Json;
  return copy;
}

export function showPath(path: JsonPath): string {
  return `/${path.join('/')}`;
}

/**
 * One random mutation of `value`; `skip` excludes paths (e.g. large data URIs whose bytes other
 * mutators handle). Returns the mutant and a note saying what was done.
 */
export function mutateJson(value: Json, random: Random, options: { extra?: readonly Json[]; skip?: (path: JsonPath) => boolean } = {}): { value: Json; note: string } {
  const all = jsonPaths(value).filter((p) => !(options.skip?.(p) ?? false));
  const path = random.pick(all.length > 0 ? all : [[]]);
  const current = getAt(value, path);
  const pool = options.extra ? [...BOUNDARY_VALUES, ...options.extra, ...options.extra] : BOUNDARY_VALUES;
  const op = random.int(10);
  const at = showPath(path);
  if (op <= 3 || path.length === 0) {
    const replacement = typeof current === 'number' && random.chance(0.5) ? nudge(current, random) : random.pick(pool);
    return { value: setAt(value, path, replacement), note: `${at} = ${JSON.stringify(replacement)?.slice(0, 60)}` };
  }
  if (op === 4) return { value: setAt(value, path, undefined), note: `delete ${at}` };
  if (op === 5 && Array.isArray(current) && current.length > 0) {
    const copy = [...current];
    const i = random.int(copy.length);
    if (random.chance(0.5)) copy.push(copy[i]!);
    else copy.splice(random.int(copy.length), 0, copy[i]!);
    return { value: setAt(value, path, copy), note: `duplicate ${at}/${i}` };
  }
  if (op === 6 && Array.isArray(current) && current.length > 1) {
    const copy = [...current].reverse();
    return { value: setAt(value, path, copy), note: `reverse ${at}` };
  }
  if (op === 7 && current !== null && typeof current === 'object' && !Array.isArray(current)) {
    const key = random.pick(['extensions', 'extras', 'name', 'uri', 'index', 'count', 'bufferView', 'byteOffset', 'sparse', 'unknownKey', 'texCoord', 'scale', 'strength', 'KHR_texture_transform']);
    const replacement = random.pick(pool);
    return { value: setAt(value, [...path, key], replacement), note: `${at}/${key} = ${JSON.stringify(replacement)?.slice(0, 60)}` };
  }
  if (op === 8) return { value: setAt(value, path, random.chance(0.5) ? [current] : { value: current }), note: `wrap ${at}` };
  if (typeof current === 'string') return { value: setAt(value, path, current + random.pick(['x', '\u0000', '/..', '%00', ' ', '\uFFFD'])), note: `append to ${at}` };
  const replacement = random.pick(pool);
  return { value: setAt(value, path, replacement), note: `${at} = ${JSON.stringify(replacement)?.slice(0, 60)}` };
}
