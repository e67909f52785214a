/**
 * The `gltf` key of a scene JSON file: one reference or an array; a reference is a string
 * (`"model.glb"`) or an object with `src` and optional `camera`, `variant`, `scene`, `animation`,
 * `time` and `transform` (see src/io/gltf/scene-file-references.ts, which loads and merges them).
 * Checking the value is part of parsing the scene file, so it lives here, below the loaders.
 */
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { describe } from '../errors/validate.ts';
import { maxCoordinateMagnitude } from './limits.ts';

export interface GltfSceneReference {
  src: string;
  camera?: number | string;
  variant?: string;
  scene?: number | string;
  animation?: number | string | null;
  time?: number;
  /** Column-major 4x4 applied to the whole asset; default identity. */
  transform?: number[];
}

function invalid(field: string, message: string): never {
  throw new GpuRendererError('INVALID_SCENE_FILE', message, { field });
}

/** Checks the `gltf` value of a scene file; errors are INVALID_SCENE_FILE naming `gltf[i].key`. */
export function parseGltfReferences(value: unknown, field = 'gltf'): GltfSceneReference[] {
  const list = Array.isArray(value) ? value : [value];
  return list.map((entry: unknown, i) => {
    const at = Array.isArray(value) ? `${field}[${i}]` : field;
    if (typeof entry === 'string') return { src: entry };
    if (typeof entry !== 'object' || entry === null || Array.isArray(entry)) invalid(at, `expected a file name or { src, ... }, got ${describe(entry)}`);
    const object = entry as Record<string, unknown>;
    const allowed = ['src', 'camera', 'variant', 'scene', 'animation', 'time', 'transform'];
    for (const key of Object.keys(object)) if (!allowed.includes(key)) invalid(`${at}.${key}`, `unknown key ${JSON.stringify(key)} (expected one of ${allowed.join(', ')})`);
    if (typeof object.src !== 'string' || object.src === '') invalid(`${at}.src`, `expected a file name, got ${describe(object.src)}`);
    const ref: GltfSceneReference = { src: object.src };
    for (const key of ['camera', 'scene'] as const) {
      const v = object[key];
      if (v === undefined) continue;
      if (typeof v !== 'string' && !(typeof v === 'number' && Number.isInteger(v) && v >= 0)) invalid(`${at}.${key}`, `expected a name or an index, got ${describe(v)}`);
      ref[key] = v;
    }
    if (object.animation !== undefined) {
      const v = object.animation;
      if (v !== null && typeof v !== 'string' && !(typeof v === 'number' && Number.isInteger(v) && v >= 0)) invalid(`${at}.animation`, `expected a name, an index or null, got ${describe(v)}`);
      ref.animation = v;
    }
    if (object.time !== undefined) {
      if (typeof object.time !== 'number' || !Number.isFinite(object.time) || object.time < 0) invalid(`${at}.time`, `expected seconds >= 0, got ${describe(object.time)}`);
      ref.time = object.time;
    }
    if (object.variant !== undefined) {
      if (typeof object.variant !== 'string') invalid(`${at}.variant`, `expected a variant name, got ${describe(object.variant)}`);
      ref.variant = object.variant;
    }
    if (object.transform !== undefined) {
      const t = object.transform;
      if (!Array.isArray(t) || t.length !== 16) invalid(`${at}.transform`, `expected 16 numbers (column-major 4x4), got ${describe(t)}`);
      t.forEach((x, k) => {
        if (typeof x !== 'number' || !Number.isFinite(x)) invalid(`${at}.transform[${k}]`, `expected a finite number, got ${describe(x)}`);
        if (Math.abs(x) > maxCoordinateMagnitude) invalid(`${at}.transform[${k}]`, `|${x}| exceeds the largest supported coordinate ${maxCoordinateMagnitude}`);
      });
      if (t[3] !== 0 || t[7] !== 0 || t[11] !== 0 || t[15] !== 1 || linearDeterminant(t) === 0) invalid(`${at}.transform`, 'expected an affine, invertible matrix (last row 0, 0, 0, 1)');
      ref.transform = t as number[];
    }
    return ref;
  });
}

/** Determinant of the linear part of a column-major 4x4. */
function linearDeterminant(m: readonly number[]): number {
  return m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) + m[8] * (m[1] * m[6] - m[5] * m[2]);
}
