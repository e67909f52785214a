/**
 * Output file patterns of a sequence: a run of `#` becomes the frame number, zero-padded to the
 * run's length (`shot-####.png` -> shot-0007.png; longer numbers are not cut), `{variant}` the
 * KHR_materials_variants name and `{camera}` the glTF camera's name, with characters outside
 * [A-Za-z0-9._-] replaced by `_`.
 */
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';

export interface OutputPatternValues {
  frame: number;
  variant?: string | undefined;
  camera?: string | undefined;
}

export function hasFramePlaceholder(pattern: string): boolean {
  return /#+/.test(pattern);
}

export function hasVariantPlaceholder(pattern: string): boolean {
  return pattern.includes('{variant}');
}

export function hasCameraPlaceholder(pattern: string): boolean {
  return pattern.includes('{camera}');
}

/** A variant name made safe for a file name. */
export function fileSafeName(name: string): string {
  const safe = name.replace(/[^A-Za-z0-9._-]/g, '_');
  return safe === '' || /^\.+$/.test(safe) ? '_' : safe;
}

export function expandOutputPattern(pattern: string, values: OutputPatternValues): string {
  let out = pattern.replace(/#+/g, (run) => String(values.frame).padStart(run.length, '0'));
  if (values.variant !== undefined) out = out.replaceAll('{variant}', fileSafeName(values.variant));
  if (values.camera !== undefined) out = out.replaceAll('{camera}', fileSafeName(values.camera));
  return out;
}

/**
 * The output path of every item, checked: several frames need `#` in the pattern, several variants
 * `{variant}`, several cameras `{camera}`, and no two items may land on one file (errors name `field`).
 */
export function outputPaths(pattern: string, items: readonly OutputPatternValues[], field = 'out'): string[] {
  const frames = new Set(items.map((i) => i.frame));
  const variants = new Set(items.map((i) => i.variant));
  if (frames.size > 1 && !hasFramePlaceholder(pattern)) {
    throw new GpuRendererError('INVALID_OPTION', `${frames.size} frames need a frame number in the file name: put #### where it goes (e.g. shot-####.png)`, { field });
  }
  if (variants.size > 1 && !hasVariantPlaceholder(pattern)) {
    throw new GpuRendererError('INVALID_OPTION', `${variants.size} variants need {variant} in the file name (e.g. shoe-{variant}.png)`, { field });
  }
  const cameras = new Set(items.map((i) => i.camera));
  if (cameras.size > 1 && !hasCameraPlaceholder(pattern)) {
    throw new GpuRendererError('INVALID_OPTION', `${cameras.size} cameras need {camera} in the file name (e.g. room-{camera}.png)`, { field });
  }
  const seen = new Map<string, OutputPatternValues>();
  return items.map((item) => {
    const path = expandOutputPattern(pattern, item);
    const other = seen.get(path);
    if (other !== undefined) {
      const what = (v: OutputPatternValues): string => [`frame ${v.frame}`, v.variant === undefined ? '' : `variant ${JSON.stringify(v.variant)}`, v.camera === undefined ? '' : `camera ${JSON.stringify(v.camera)}`].filter((t) => t !== '').join(' ');
      throw new GpuRendererError('INVALID_OPTION', `${what(item)} and ${what(other)} would both be written to ${path}`, { field });
    }
    seen.set(path, item);
    return path;
  });
}
