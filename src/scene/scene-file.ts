/**
 * The scene JSON file format: a `WavefrontSceneDescription` written as JSON. This parser checks the
 * structure (object shapes, key names, value types) and reports the first problem as a typed
 * `INVALID_SCENE_FILE` error naming its field path (`meshes[1].positions[4]`). Geometric checks
 * that need the whole mesh (index ranges, degenerate triangles, sizes) are the renderer's mesh
 * normaliser's job and happen when the scene is uploaded.
 */
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { describe } from '../errors/validate.ts';
import { anyMaterialExtensions } from '../materials/extensions/index.ts';
import { parseGltfReferences, type GltfSceneReference } from './gltf-references.ts';
import { sceneObjectMaterialKinds, type SceneObjectMaterialKind } from './scene-object.ts';
import type {
  WavefrontCameraInput,
  WavefrontEnvironmentInput,
  WavefrontImageInput,
  WavefrontInstanceInput,
  WavefrontMaterialInput,
  WavefrontMeshInput,
  WavefrontSamplerInput,
  WavefrontSceneDescription,
  WavefrontSceneObjectInput,
  WavefrontTextureInput,
  WavefrontTextureRefInput,
  WavefrontTextureTransformInput,
} from './types.ts';

type Json = Record<string, unknown>;

/** An image a scene file names by location (a path or URL relative to the file, or a data URI). */
export interface WavefrontImageReference {
  uri: string;
}

/**
 * An environment map a scene file names by location (a .hdr or .exr file relative to the scene
 * file, a URL or a data URI), with its radiance multiplier and rotation about +Y in degrees.
 */
export interface WavefrontEnvironmentMapReference {
  map: string;
  intensity?: number;
  rotationDegrees?: number;
  /**
   * Channel values below zero (the ringing of lossy OpenEXR compression): 'error' refuses the map,
   * 'zero' sets them to 0 and reports it. Default: the loader's `negativeTexels` option ('error').
   */
  negativeTexels?: 'error' | 'zero';
}

/**
 * What a scene file holds: a scene description whose images may be given by `uri` and whose
 * environment may be a map file, plus `gltf` references to glTF assets merged into the scene.
 * `resolveSceneFile` / `loadSceneFile` (src/io/scene-file-loader.ts) turn it into a renderer-ready
 * WavefrontSceneDescription (an environment map becomes its `environmentMap` option).
 */
export interface WavefrontSceneFile extends Omit<WavefrontSceneDescription, 'images' | 'environment'> {
  environment?: WavefrontEnvironmentInput | WavefrontEnvironmentMapReference;
  images?: (WavefrontImageInput | WavefrontImageReference)[];
  gltf?: GltfSceneReference[];
}

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

  integer(value: unknown, field: string, min: number): number {
    const n = this.number(value, field, { min });
    if (!Number.isInteger(n)) this.fail(field, `expected an integer, got ${n}`);
    return n;
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

const sceneKeys = ['camera', 'environment', 'meshes', 'instances', 'materials', 'textures', 'images', 'sceneObjects', 'lights', 'gltf'] as const;
const cameraKeys = ['type', 'position', 'target', 'up', 'fovYDegrees', 'orthographicHeight'] as const;
// Extension keys (factors and textures) come from the material extension registry.
const extensionFactors = anyMaterialExtensions.flatMap((e) => e.factors);
const textureSlots = [
  'baseColorTexture', 'metallicRoughnessTexture', 'normalTexture', 'occlusionTexture', 'emissiveTexture',
  ...anyMaterialExtensions.flatMap((e) => e.textures.map((t) => t.key)),
];
const scalarFactors = [
  'metallicFactor', 'roughnessFactor', 'emissiveStrength', 'ior', 'alphaCutoff', ...extensionFactors.filter((f) => f.type === 'number').map((f) => f.key),
];
const colorFactors = ['emissiveFactor', ...extensionFactors.filter((f) => f.type === 'rgb').map((f) => f.key)];
const materialKeys = ['name', 'baseColorFactor', 'doubleSided', 'alphaMode', ...scalarFactors, ...colorFactors, ...textureSlots];
const meshKeys = ['id', 'positions', 'indices', 'normals', 'tangents', 'uvs', 'uvs1', 'colors', 'material', 'emission'] as const;
const sceneObjectKeys = ['type', 'center', 'radius', 'min', 'max', 'color', 'emission', 'roughness', 'metallic', 'ior', 'materialKind'] as const;

/**
 * Parses and structurally validates a scene JSON file. `path` only labels error messages.
 * Throws `GpuRendererError` with code `INVALID_SCENE_FILE` and `field` set to the offending path.
 */
export function parseSceneFile(jsonText: string, path?: string): WavefrontSceneFile {
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
export function validateSceneDescription(value: unknown, path?: string): WavefrontSceneFile {
  return validate(value, new SceneFileReader(path));
}

function validate(value: unknown, r: SceneFileReader): WavefrontSceneFile {
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
      type: (x, g) => {
        if (x !== 'perspective' && x !== 'orthographic') r.fail(g, `expected "perspective" or "orthographic", got ${describe(x)}`);
        return x;
      },
      position: vec3,
      target: vec3,
      up: vec3,
      fovYDegrees: (x, g) => r.number(x, g, { min: 0, max: 180, exclusiveMin: true }),
      orthographicHeight: (x, g) => r.number(x, g, { min: 0, exclusiveMin: true }),
    });
  };

  // `{ color }` (uniform radiance) or `{ map, intensity?, rotationDegrees? }` (an environment map file).
  const environment = (v: unknown, f: string): WavefrontEnvironmentInput | WavefrontEnvironmentMapReference => {
    const o = r.object(v, f, ['color', 'map', 'intensity', 'rotationDegrees', 'negativeTexels']);
    if (o.map !== undefined) {
      if (o.color !== undefined) r.fail(join(f, 'color'), 'an environment is either { color } or { map, intensity?, rotationDegrees?, negativeTexels? }');
      const map = r.string(o.map, join(f, 'map'));
      if (map === '') r.fail(join(f, 'map'), 'expects a file name or URL');
      return pick<WavefrontEnvironmentMapReference>(o, f, {
        map: () => map,
        intensity: (x, g) => r.number(x, g, { min: 0 }),
        rotationDegrees: (x, g) => r.number(x, g),
        negativeTexels: (x, g) => {
          if (x !== 'error' && x !== 'zero') r.fail(g, `expected "error" or "zero", got ${describe(x)}`);
          return x;
        },
      });
    }
    for (const key of ['intensity', 'rotationDegrees', 'negativeTexels'] as const) if (o[key] !== undefined) r.fail(join(f, key), 'applies to an environment map ({ map })');
    if (o.color === undefined) r.fail(join(f, 'color'), 'is required (or give a map)');
    return { color: vec3(o.color, join(f, 'color')) };
  };

  const textureRef = (v: unknown, f: string): WavefrontTextureRefInput => {
    const o = r.object(v, f, ['index', 'texCoord', 'transform', 'scale', 'strength']);
    if (o.index === undefined) r.fail(join(f, 'index'), 'is required');
    return pick<WavefrontTextureRefInput>(o, f, {
      index: (x, g) => r.integer(x, g, 0),
      texCoord: (x, g) => r.integer(x, g, 0),
      transform: (x, g) =>
        pick<WavefrontTextureTransformInput>(r.object(x, g, ['offset', 'rotation', 'scale', 'texCoord']), g, {
          offset: (y, h) => r.numbers(y, h, [2]),
          rotation: (y, h) => r.number(y, h),
          scale: (y, h) => r.numbers(y, h, [2]),
          texCoord: (y, h) => r.integer(y, h, 0),
        }),
      scale: (x, g) => r.number(x, g),
      strength: (x, g) => r.number(x, g),
    });
  };

  const material = (v: unknown, f: string): WavefrontMaterialInput => {
    const o = r.object(v, f, materialKeys);
    const out: Record<string, unknown> = {};
    for (const key of Object.keys(o)) {
      const g = join(f, key);
      if (key === 'name') out[key] = r.string(o[key], g);
      else if (key === 'baseColorFactor') out[key] = r.numbers(o[key], g, [3, 4]);
      else if (key === 'doubleSided') out[key] = r.boolean(o[key], g);
      else if (key === 'alphaMode') {
        if (o[key] !== 'OPAQUE' && o[key] !== 'MASK' && o[key] !== 'BLEND') r.fail(g, `expected "OPAQUE", "MASK" or "BLEND", got ${describe(o[key])}`);
        out[key] = o[key];
      } else if ((colorFactors as readonly string[]).includes(key)) out[key] = vec3(o[key], g);
      else if ((scalarFactors as readonly string[]).includes(key)) out[key] = key === 'metallicFactor' || key === 'roughnessFactor' ? unit(o[key], g) : key === 'emissiveStrength' ? nonNegative(o[key], g) : r.number(o[key], g);
      else out[key] = textureRef(o[key], g);
    }
    return out as WavefrontMaterialInput;
  };

  const sampler = (v: unknown, f: string): WavefrontSamplerInput => {
    const o = r.object(v, f, ['wrapS', 'wrapT', 'magFilter', 'minFilter']);
    const oneOf = <T extends string>(allowed: readonly T[]) => (x: unknown, g: string): T => {
      if (!allowed.includes(x as T)) r.fail(g, `expected one of ${allowed.join(', ')}, got ${describe(x)}`);
      return x as T;
    };
    const wrap = oneOf(['repeat', 'clamp-to-edge', 'mirrored-repeat'] as const);
    return pick<WavefrontSamplerInput>(o, f, {
      wrapS: wrap,
      wrapT: wrap,
      magFilter: oneOf(['nearest', 'linear'] as const),
      minFilter: oneOf(['nearest', 'linear', 'nearest-mipmap-nearest', 'linear-mipmap-nearest', 'nearest-mipmap-linear', 'linear-mipmap-linear'] as const),
    });
  };

  const texture = (v: unknown, f: string): WavefrontTextureInput => {
    const o = r.object(v, f, ['name', 'image', 'sampler']);
    if (o.image === undefined) r.fail(join(f, 'image'), 'is required');
    return pick<WavefrontTextureInput>(o, f, {
      name: (x, g) => r.string(x, g),
      image: (x, g) => r.integer(x, g, 0),
      sampler,
    });
  };

  const image = (v: unknown, f: string): WavefrontImageInput | WavefrontImageReference => {
    const o = r.object(v, f, ['width', 'height', 'data', 'uri']);
    if (o.uri !== undefined) {
      if (Object.keys(o).length > 1) r.fail(f, 'an image is either { uri } or { width, height, data }');
      return { uri: r.string(o.uri, join(f, 'uri')) };
    }
    for (const key of ['width', 'height', 'data'] as const) if (o[key] === undefined) r.fail(join(f, key), 'is required');
    return { width: r.integer(o.width, join(f, 'width'), 1), height: r.integer(o.height, join(f, 'height'), 1), data: Uint8Array.from(r.numbers(o.data, join(f, 'data'))) };
  };

  const instance = (v: unknown, f: string): WavefrontInstanceInput => {
    const o = r.object(v, f, ['id', 'mesh', 'transform', 'material']);
    if (o.mesh === undefined) r.fail(join(f, 'mesh'), 'is required');
    return pick<WavefrontInstanceInput>(o, f, {
      id: (x, g) => (typeof x === 'number' ? r.number(x, g) : r.string(x, g)),
      mesh: (x, g) => r.integer(x, g, 0),
      transform: (x, g) => r.numbers(x, g, [16]),
      material: (x, g) => r.integer(x, g, 0),
    });
  };

  const mesh = (v: unknown, f: string): WavefrontMeshInput => {
    const o = r.object(v, f, meshKeys);
    if (o.positions === undefined) r.fail(join(f, 'positions'), 'is required');
    return pick<WavefrontMeshInput>(o, f, {
      id: (x, g) => (typeof x === 'number' ? r.number(x, g) : r.string(x, g)),
      positions: (x, g) => r.numbers(x, g),
      indices: (x, g) => r.numbers(x, g),
      normals: (x, g) => r.numbers(x, g),
      tangents: (x, g) => r.numbers(x, g),
      uvs: (x, g) => r.numbers(x, g),
      uvs1: (x, g) => r.numbers(x, g),
      colors: (x, g) => r.numbers(x, g),
      material: (x, g) => (typeof x === 'number' ? r.integer(x, g, 0) : material(x, g)),
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
      materialKind: (x, g) => {
        if (!sceneObjectMaterialKinds.includes(x as SceneObjectMaterialKind)) r.fail(g, `expected one of ${sceneObjectMaterialKinds.join(', ')}, got ${describe(x)}`);
        return x as SceneObjectMaterialKind;
      },
    });
  };

  const list = <T>(item: (v: unknown, f: string) => T) => (v: unknown, f: string): T[] => r.array(v, f).map((x, i) => item(x, `${f}[${i}]`));

  return pick<WavefrontSceneFile>(root, '', {
    camera,
    environment,
    meshes: list(mesh),
    instances: list(instance),
    materials: list(material),
    textures: list(texture),
    images: list(image),
    sceneObjects: list(sceneObject),
    // Lights are validated by the renderer, which names the field of any problem.
    lights: (x, g) => r.array(x, g) as never,
    gltf: (x, g) => parseGltfReferences(x, g),
  });
}
