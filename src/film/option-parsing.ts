/**
 * String parsers for the output options a command line (or a config file) passes as text; the CLI
 * argument parser wires them to flags such as `--time-limit 2m30s` and `--aovs albedo,normal`.
 */
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { wavefrontAovNames, type WavefrontAovName } from './aovs.ts';

const unitMs: Record<string, number> = { ms: 1, s: 1000, m: 60_000, h: 3_600_000 };

/**
 * A duration in milliseconds from text: one or more `<number><unit>` parts with units ms, s, m, h
 * (`'30s'`, `'1.5m'`, `'1h30m'`, `'250ms'`), or a bare number of seconds (`'45'`). Whitespace around
 * the text is ignored; the result must be finite and > 0.
 */
export function parseDuration(text: string, field = 'duration'): number {
  const fail = (why: string): never => {
    throw new GpuRendererError('INVALID_OPTION', `${why}: expected e.g. 30s, 1m30s, 250ms, 2h or a number of seconds, got ${JSON.stringify(text)}`, { field });
  };
  if (typeof text !== 'string') fail('not text');
  const trimmed = text.trim();
  if (/^\d+(\.\d+)?$/.test(trimmed)) {
    const seconds = Number(trimmed);
    if (!(seconds > 0)) fail('must be > 0');
    return seconds * 1000;
  }
  const part = /(\d+(?:\.\d+)?)(ms|s|m|h)/gy;
  let total = 0;
  let consumed = 0;
  for (let match = part.exec(trimmed); match; match = part.exec(trimmed)) {
    total += Number(match[1]) * unitMs[match[2]];
    consumed = part.lastIndex;
  }
  if (consumed === 0 || consumed !== trimmed.length) fail('not a duration');
  if (!(total > 0) || !Number.isFinite(total)) fail('must be > 0');
  return total;
}

/**
 * A comma-separated AOV list (`'albedo,normal,objectId'`), case-insensitive, blanks ignored, duplicates
 * dropped, order kept; `''` and `'none'` give an empty list. Unknown names are typed errors.
 */
export function parseAovList(text: string, field = 'aovs'): WavefrontAovName[] {
  if (typeof text !== 'string') throw new GpuRendererError('INVALID_OPTION', `expected text, got ${typeof text}`, { field });
  const names = text
    .split(',')
    .map((s) => s.trim().toLowerCase())
    .filter((s) => s !== '');
  if (names.length === 1 && names[0] === 'none') return [];
  const out: WavefrontAovName[] = [];
  for (const lower of names) {
    const name = wavefrontAovNames.find((n) => n.toLowerCase() === lower);
    if (name === undefined) {
      throw new GpuRendererError('INVALID_OPTION', `unknown AOV ${JSON.stringify(lower)} (expected a comma-separated list of ${wavefrontAovNames.join(', ')})`, { field });
    }
    if (!out.includes(name)) out.push(name);
  }
  return out;
}
