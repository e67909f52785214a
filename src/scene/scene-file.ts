/**
 * The scene JSON file format: a `WavefrontSceneDescription` written as JSON. This parser checks the
 * structure (object shapes, key names, value types) and reports the first problem as a typed
 * `INVALID_SCENE_FILE` error naming its field path (`meshes[1].positions[4]`). Geometric checks
 * that need the whole mesh (index ranges, degenerate triangles, sizes) are the renderer's mesh
 * normaliser's job and happen when the scene is uploaded.
 */
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { describe } from '../errors/validate.ts';
import type {
  WavefrontCameraInput,
  WavefrontEnvironmentInput,
  WavefrontMaterialInput,
  WavefrontMeshInput,
  WavefrontSceneDescription,
  WavefrontSceneObjectInput,
} from './types.ts';

type Json = Record<string, unknown>;

class SceneFileReader {
  readonly path: string | undefined;

  constructor(path: string | undefined) {
    this.path = path;
  }

  fail(field: string | undefined, message: string): never {
    const where = this.path === undefined ? '' : ` (in ${this.path})`;
    throw new GpuRendererError('INVALID_SCENE_FILE', `${message}${where}`, field === undefined ? {} : { field });
  }

  object(value: unknown, field: string, allowed: readonly string[]): Json {
    if (typeof value !== 'object' || value === null || Array.isArray(value)) this.fail(field, `expected an object, got ${describe(value)}`);
    for (const key of Object.keys(value)) {
      if (!allowed.includes(key)) this.fail(join(field, key), `unknown key ${JSON.stringify(key)} (expected one of ${allowed.join(', ')})`);
    }
    return value as Json;
  }

  number(value: unknown, field: string, range: { min?: number; max?: number; exclusiveMin?: boolean } = {}): number {
    if (typeof value !== 'number' || !Number.isFinite(value)) this.fail(field, `expected a finite number, got ${describe(value)}`);
    if (range.min !== undefined && (range.exclusiveMin ? value <= range.min : value < range.min)) {
      this.fail(field, `must be ${range.exclusiveMin ? '>' : '>='} ${range.min}, got ${value}`);
    }
    if (range.max !== undefined && value > range.max) this.fail(field, `must be <= ${range.max}, got ${value}`);
    return value;
  }

  numbers(value: unknown, field: string, lengths?: readonly number[]): number[] {
    if (!Array.isArray(value)) this.fail(field, `expected an array of numbers, got ${describe(value)}`);
    if (lengths !== undefined && !lengths.includes(value.length)) {
      this.fail(field, `expected ${lengths.join(' or ')} numbers, got ${value.length}`);
    }
    for (let i = 0; i < value.length; i++) {
      const v: unknown = value[i];
      if (typeof v !== 'number' || !Number.isFinite(v)) this.fail(`${field}[${i}]`, `expected a finite number, got ${describe(v)}`);
    }
    return value as number[];
  }

  string(value: unknown, field: string): string {
    if (typeof value !== 'string') this.fail(field, `expected a string, got ${describe(value)}`);
    return value;
  }

  boolean(value: unknown, field: string): boolean {
    if (typeof value !== 'boolean') this.fail(field, `expected true or false, got ${describe(value)}`);
    return value;
  }

  array(value: unknown, field: string): unknown[] {
    if (!Array.isArray(value)) this.fail(field, `expected an array, got ${describe(value)}`);
    return value;
  }
}

function join(field: string, key: string): string {
  return field === '' ? key : `${field}.${key}`;
}

/** Copies the keys of `src` present in `readers`, each through its reader. */
function pick<T>(src: Json, field: string, readers: { [K in keyof T]-?: (value: unknown, field: string) => T[K] }): T {
  const out: Record<string, unknown> = {};
  for (const key of Object.keys(readers) as (keyof T & string)[]) {
    if (src[key] !== undefined) out[key] = readers[key](src[key], join(field, key));
  }
  return out as T;
}

const sceneKeys = ['camera', 'environment', 'meshes', 'sceneObjects'] as const;
const cameraKeys = ['position', 'target', 'up', 'fovYDegrees'] as const;
const materialKeys = ['baseColorFactor', 'metallicFactor', 'roughnessFactor', 'emissiveFactor', 'emissiveStrength', 'ior', 'doubleSided'] as const;
const meshKeys = ['id', 'positions', 'indices', 'normals', 'uvs', 'material', 'emission'] as const;
const sceneObjectKeys = ['type', 'center', 'radius', 'min', 'max', 'color', 'emission', 'roughness', 'metallic', 'ior', 'materialKind'] as const;

/**
 * Parses and structurally validates a scene JSON file. `path` only labels error messages.
 * Throws `GpuRendererError` with code `INVALID_SCENE_FILE` and `field` set to the offending path.
 */
export function parseSceneFile(jsonText: string, path?: string): WavefrontSceneDescription {
  const r = new SceneFileReader(path);
  let root: unknown;
  try {
    root = JSON.parse(jsonText);
  } catch (error) {
    r.fail(undefined, `not valid JSON: ${(error as Error).message}`);
  }
  return validate(root, r);
}

/**
 * Validates an already-parsed scene object (what a scene JSON file holds) the same way; `path`
 * only labels error messages.
 */
export function validateSceneDescription(value: unknown, path?: string): WavefrontSceneDescription {
  return validate(value, new SceneFileReader(path));
}

function validate(value: unknown, r: SceneFileReader): WavefrontSceneDescription {
  if (typeof value !== 'object' || value === null || Array.isArray(value)) r.fail(undefined, `a scene file holds a JSON object, got ${describe(value)}`);
  const root = r.object(value, '', sceneKeys);

  const vec3 = (v: unknown, f: string): number[] => r.numbers(v, f, [3]);
  const vec4 = (v: unknown, f: string): number[] => r.numbers(v, f, [4]);
  const nonNegative = (v: unknown, f: string): number => r.number(v, f, { min: 0 });
  const unit = (v: unknown, f: string): number => r.number(v, f, { min: 0, max: 1 });

  const camera = (v: unknown, f: string): WavefrontCameraInput => {
    const o = r.object(v, f, cameraKeys);
    for (const key of ['position', 'target'] as const) if (o[key] === undefined) r.fail(join(f, key), 'is required');
    return pick<WavefrontCameraInput>(o, f, {
      position: vec3,
      target: vec3,
      up: vec3,
      fovYDegrees: (x, g) => r.number(x, g, { min: 0, max: 180, exclusiveMin: true }),
    });
  };

  const environment = (v: unknown, f: string): WavefrontEnvironmentInput => {
    const o = r.object(v, f, ['color']);
    if (o.color === undefined) r.fail(join(f, 'color'), 'is required');
    return { color: vec3(o.color, join(f, 'color')) };
  };

  const material = (v: unknown, f: string): WavefrontMaterialInput =>
    pick<WavefrontMaterialInput>(r.object(v, f, materialKeys), f, {
      baseColorFactor: (x, g) => r.numbers(x, g, [3, 4]),
      metallicFactor: unit,
      roughnessFactor: unit,
      emissiveFactor: vec3,
      emissiveStrength: nonNegative,
      ior: (x, g) => r.number(x, g),
      doubleSided: (x, g) => r.boolean(x, g),
    });

  const mesh = (v: unknown, f: string): WavefrontMeshInput => {
    const o = r.object(v, f, meshKeys);
    if (o.positions === undefined) r.fail(join(f, 'positions'), 'is required');
    return pick<WavefrontMeshInput>(o, f, {
      id: (x, g) => (typeof x === 'number' ? r.number(x, g) : r.string(x, g)),
      positions: (x, g) => r.numbers(x, g),
      indices: (x, g) => r.numbers(x, g),
      normals: (x, g) => r.numbers(x, g),
      uvs: (x, g) => r.numbers(x, g),
      material,
      emission: vec4,
    });
  };

  const sceneObject = (v: unknown, f: string): WavefrontSceneObjectInput => {
    const o = r.object(v, f, sceneObjectKeys);
    if (o.type !== 'sphere' && o.type !== 'box') r.fail(join(f, 'type'), `expected "sphere" or "box", got ${describe(o.type)}`);
    return pick<WavefrontSceneObjectInput>(o, f, {
      type: () => o.type as 'sphere' | 'box',
      center: vec3,
      radius: (x, g) => r.number(x, g, { min: 0, exclusiveMin: true }),
      min: vec3,
      max: vec3,
      color: vec3,
      emission: vec4,
      roughness: unit,
      metallic: unit,
      ior: (x, g) => r.number(x, g),
      materialKind: (x, g) => r.string(x, g),
    });
  };

  const list = <T>(item: (v: unknown, f: string) => T) => (v: unknown, f: string): T[] => r.array(v, f).map((x, i) => item(x, `${f}[${i}]`));

  return pick<WavefrontSceneDescription>(root, '', {
    camera,
    environment,
    meshes: list(mesh),
    sceneObjects: list(sceneObject),
  });
}
