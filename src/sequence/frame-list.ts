/**
 * Frame lists as users write them: `0-23` (inclusive, as Blender's -s/-e and vk_gltf_renderer's
 * --frames), `0-239:10` (every tenth), `1,5,9`, or any comma-separated mix. Frames are integers
 * >= 0, each listed once, rendered in the order given.
 */
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';

/** Most frames one list may name (a typo like 0-1000000000 is an error, not an hour of allocation). */
export const maxSequenceFrames = 1_000_000;

function invalid(field: string, message: string): never {
  throw new GpuRendererError('INVALID_OPTION', message, { field });
}

/** Parses a frame list; errors are INVALID_OPTION naming `field` and quoting the bad item. */
export function parseFrameList(text: string, field = 'frames'): number[] {
  const frames: number[] = [];
  const seen = new Set<number>();
  const items = text.split(',').map((item) => item.trim());
  if (text.trim() === '') invalid(field, 'expected frames such as 0-23, 0-23:2 or 1,5,9');
  for (const item of items) {
    const match = /^(\d+)(?:-(\d+)(?::(\d+))?)?$/.exec(item);
    if (match === null) invalid(field, `cannot read ${JSON.stringify(item)}: expected a frame (7), a range (0-23) or a range with a step (0-23:2)`);
    const first = Number(match[1]);
    const last = match[2] === undefined ? first : Number(match[2]);
    const step = match[3] === undefined ? 1 : Number(match[3]);
    if (last < first) invalid(field, `range ${JSON.stringify(item)} ends before it starts`);
    if (step < 1) invalid(field, `range ${JSON.stringify(item)} has step 0`);
    if (frames.length + Math.floor((last - first) / step) + 1 > maxSequenceFrames) invalid(field, `more than ${maxSequenceFrames} frames`);
    for (let f = first; f <= last; f += step) {
      if (seen.has(f)) invalid(field, `frame ${f} is listed twice`);
      seen.add(f);
      frames.push(f);
    }
  }
  return frames;
}

/** Validates frame numbers given as an array (API and job files). */
export function checkFrameNumbers(frames: unknown, field = 'frames'): number[] {
  if (!Array.isArray(frames) || frames.length === 0) invalid(field, 'expected a non-empty array of frame numbers');
  if (frames.length > maxSequenceFrames) invalid(field, `more than ${maxSequenceFrames} frames`);
  const seen = new Set<number>();
  frames.forEach((f, i) => {
    if (typeof f !== 'number' || !Number.isInteger(f) || f < 0) invalid(`${field}[${i}]`, `expected an integer frame number >= 0, got ${JSON.stringify(f)}`);
    if (seen.has(f)) invalid(`${field}[${i}]`, `frame ${f} is listed twice`);
    seen.add(f);
  });
  return frames as number[];
}
