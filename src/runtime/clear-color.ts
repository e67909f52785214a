import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { describe, isArrayLike } from '../errors/validate.ts';

/** `"#rrggbb"`, `"#rrggbbaa"` (hex, case-insensitive) or `[r, g, b, a]` with components in [0, 1]. */
export type RendererClearColorInput = string | readonly number[];
export type RendererRgba = readonly [number, number, number, number];

const hexPattern = /^#([0-9a-f]{6}|[0-9a-f]{8})$/i;

/**
 * Parses a clear colour into RGBA in [0, 1]. The values are written to the target unchanged, so on
 * the 8-bit unorm canvas formats a hex colour is presented byte for byte (no colour-space change).
 */
export function parseClearColor(value: unknown, field = 'clearColor'): RendererRgba {
  if (typeof value === 'string') {
    if (!hexPattern.test(value)) {
      throw new GpuRendererError('INVALID_OPTION', `expected "#rrggbb" or "#rrggbbaa", got ${describe(value)}`, { field });
    }
    const hex = value.slice(1);
    const byte = (i: number): number => parseInt(hex.slice(i * 2, i * 2 + 2), 16) / 255;
    return Object.freeze([byte(0), byte(1), byte(2), hex.length === 8 ? byte(3) : 1]) as RendererRgba;
  }
  if (isArrayLike(value) && value.length === 4) {
    const out: number[] = [];
    for (let i = 0; i < 4; i++) {
      const c = value[i];
      if (typeof c !== 'number' || !Number.isFinite(c) || c < 0 || c > 1) {
        throw new GpuRendererError('INVALID_OPTION', `expected a number in [0, 1], got ${describe(c)}`, { field: `${field}[${i}]` });
      }
      out.push(c);
    }
    return Object.freeze(out) as unknown as RendererRgba;
  }
  throw new GpuRendererError('INVALID_OPTION', `expected "#rrggbb", "#rrggbbaa" or [r, g, b, a], got ${describe(value)}`, { field });
}
