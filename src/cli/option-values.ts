/**
 * The value parsers of command-line options: each reads one option's text and returns its value,
 * or throws INVALID_OPTION naming the flag. Written `(text, flag) => value`, the form of the
 * parsers the library exports for its own options (parseDuration, parseFrameList, ...), so a row
 * of an option table takes either.
 */
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';

export type ValueParser<T> = (text: string, flag: string) => T;

export function invalidOption(field: string, message: string): never {
  throw new GpuRendererError('INVALID_OPTION', message, { field });
}

/** A decimal integer in [min, max]. */
export function integer(min: number, max: number): ValueParser<number> {
  return (text, flag) => {
    if (!/^[+]?\d+$/.test(text)) invalidOption(flag, `expected an integer, got ${JSON.stringify(text)}`);
    const n = Number(text);
    if (n < min || n > max) invalidOption(flag, `must be between ${min} and ${max}, got ${n}`);
    return n;
  };
}

/** `Number(text)`, except that blank text is NaN rather than 0. */
function toNumber(text: string): number {
  return text.trim() === '' ? Number.NaN : Number(text);
}

/** A finite number, at least `min` where one is given. */
export function finiteNumber(min = -Infinity): ValueParser<number> {
  return (text, flag) => {
    const n = toNumber(text);
    if (!Number.isFinite(n) || n < min) invalidOption(flag, `expected a finite number${min > -Infinity ? ` >= ${min}` : ''}, got ${JSON.stringify(text)}`);
    return n;
  };
}

export const positiveNumber: ValueParser<number> = (text, flag) => {
  const n = toNumber(text);
  if (!Number.isFinite(n) || n <= 0) invalidOption(flag, `expected a finite number > 0, got ${JSON.stringify(text)}`);
  return n;
};

/** A number in [-limit, limit], described as `what` in the message. */
export function boundedNumber(limit: number, what: string): ValueParser<number> {
  return (text, flag) => {
    const n = toNumber(text);
    if (!Number.isFinite(n) || Math.abs(n) > limit) invalidOption(flag, `expected ${what} in [-${limit}, ${limit}], got ${JSON.stringify(text)}`);
    return n;
  };
}

/** One of a fixed set of words. */
export function oneOf<const W extends string>(...words: readonly W[]): ValueParser<W> {
  const listed = words.length === 2 ? `${words[0]} or ${words[1]}` : `${words.slice(0, -1).join(', ')} or ${words.at(-1)}`;
  return (text, flag) => {
    if (!(words as readonly string[]).includes(text)) invalidOption(flag, `expected ${listed}, got ${JSON.stringify(text)}`);
    return text as W;
  };
}

/** Any text but the empty string, which is refused as `expects <what>`. */
export function nonEmpty(what: string): ValueParser<string> {
  return (text, flag) => {
    if (text === '') invalidOption(flag, `expects ${what}`);
    return text;
  };
}

/** `all`, or names separated by commas. */
export const allOrNames: ValueParser<'all' | string[]> = (text, flag) => {
  if (text === 'all') return 'all';
  const names = text.split(',').map((n) => n.trim());
  if (names.some((n) => n === '')) invalidOption(flag, `expected all or comma-separated names, got ${JSON.stringify(text)}`);
  return names;
};

/** `x,y,z`: three finite numbers separated by commas. */
export const vector3: ValueParser<[number, number, number]> = (text, flag) => {
  const values = text.split(',').map(toNumber);
  if (values.length !== 3 || !values.every(Number.isFinite)) invalidOption(flag, `expected x,y,z (three finite numbers), got ${JSON.stringify(text)}`);
  return values as [number, number, number];
};

export interface OrbitValue {
  azimuthDegrees: number;
  elevationDegrees: number;
  distance?: number;
}

/** `azimuth,elevation[,distance]` in degrees and scene units. */
export const orbit: ValueParser<OrbitValue> = (text, flag) => {
  const values = text.split(',').map(toNumber);
  if ((values.length !== 2 && values.length !== 3) || !values.every(Number.isFinite)) {
    invalidOption(flag, `expected azimuth,elevation or azimuth,elevation,distance (finite numbers), got ${JSON.stringify(text)}`);
  }
  const [azimuthDegrees, elevationDegrees, distance] = values as [number, number, number | undefined];
  if (Math.abs(elevationDegrees) > 90) invalidOption(flag, `elevation must be within [-90, 90] degrees, got ${elevationDegrees}`);
  if (distance !== undefined && !(distance > 0)) invalidOption(flag, `distance must be > 0, got ${distance}`);
  return { azimuthDegrees, elevationDegrees, ...(distance !== undefined ? { distance } : {}) };
};

/** A vertical field of view in degrees, in (0, 179]. */
export const fieldOfView: ValueParser<number> = (text, flag) => {
  const fov = toNumber(text);
  if (!(fov > 0 && fov <= 179)) invalidOption(flag, `expected degrees in (0, 179], got ${JSON.stringify(text)}`);
  return fov;
};
