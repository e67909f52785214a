import { describe, fail, isArrayLike } from '../errors/validate.ts';
import { maxCoordinateMagnitude } from './limits.ts';
import { normalizeMaterial, type NormalizedMaterial } from './material.ts';
import type { WavefrontMeshInput } from './types.ts';


/** A validated indexed triangle mesh: its vertex streams in typed arrays (object space). */
export interface NormalizedMesh {
  id: number | string;
  positions: Float32Array;
  indices: Uint32Array;
  normals: Float32Array | null;
  /** xyzw per vertex. */
  tangents: Float32Array | null;
  uvs: Float32Array | null;
  uvs1: Float32Array | null;
  /** rgba per vertex. */
  colors: Float32Array | null;
  /** An inline material (normalised) or an index into the scene's materials. */
  material: NormalizedMaterial | number;
  vertexCount: number;
  triangleCount: number;
}

function finiteArray(value: unknown, field: string, itemsPerVertex: number, bound = Infinity): Float32Array {
  if (!isArrayLike(value)) fail('INVALID_MESH', field, `expected an array of numbers, got ${describe(value)}`);
  if (value.length % itemsPerVertex !== 0) fail('INVALID_MESH', field, `length ${value.length} is not a multiple of ${itemsPerVertex}`);
  const out = new Float32Array(value.length);
  for (let i = 0; i < value.length; i++) {
    const v = value[i];
    if (typeof v !== 'number' || !Number.isFinite(v)) fail('INVALID_MESH', `${field}[${i}]`, `expected a finite number, got ${describe(v)}`);
    if (Math.abs(v) > bound) fail('INVALID_MESH', `${field}[${i}]`, `|${v}| exceeds the largest supported coordinate ${bound}`);
    out[i] = v;
  }
  return out;
}

function stream(value: unknown, field: string, itemsPerVertex: number, vertexCount: number): Float32Array | null {
  if (value === undefined) return null;
  const out = finiteArray(value, field, itemsPerVertex);
  if (out.length / itemsPerVertex !== vertexCount) fail('INVALID_MESH', field, `has ${out.length / itemsPerVertex} vertices but positions has ${vertexCount}`);
  return out;
}

function colorsOf(value: unknown, field: string, vertexCount: number): Float32Array | null {
  if (value === undefined) return null;
  if (!isArrayLike(value)) fail('INVALID_MESH', field, `expected an array of numbers, got ${describe(value)}`);
  const components = value.length === 3 * vertexCount ? 3 : value.length === 4 * vertexCount ? 4 : 0;
  if (components === 0) fail('INVALID_MESH', field, `expected 3 or 4 numbers per vertex for ${vertexCount} vertices, got ${value.length}`);
  const raw = finiteArray(value, field, components);
  const out = new Float32Array(4 * vertexCount);
  for (let v = 0; v < vertexCount; v++) {
    for (let c = 0; c < 4; c++) {
      const x = c < components ? raw[components * v + c]! : 1;
      if (x < 0 || x > 1) fail('INVALID_MESH', `${field}[${components * v + c}]`, `vertex colours are in [0, 1], got ${x}`);
      out[4 * v + c] = x;
    }
  }
  return out;
}

/**
 * Validates one mesh at the public boundary: finite streams of consistent lengths, an index list
 * that is a multiple of 3 and in range, tangents with w = +-1, colours in [0, 1], a material
 * (inline, or an index below `materialCount`). Errors name the field, e.g. `meshes[2].indices[5]`.
 */
export function normalizeWavefrontMesh(input: WavefrontMeshInput, index = 0, fieldPrefix = `meshes[${index}]`, context: { materialCount?: number; textureCount?: number } = {}): NormalizedMesh {
  if (typeof input !== 'object' || input === null) fail('INVALID_MESH', fieldPrefix, 'expected a mesh object');
  for (const key of Object.keys(input)) {
    if (!['id', 'positions', 'indices', 'normals', 'tangents', 'uvs', 'uvs1', 'colors', 'material', 'emission'].includes(key)) {
      fail('INVALID_MESH', `${fieldPrefix}.${key}`, 'unknown mesh key');
    }
  }
  const positions = finiteArray(input.positions, `${fieldPrefix}.positions`, 3, maxCoordinateMagnitude);
  const vertexCount = positions.length / 3;
  if (vertexCount === 0) fail('INVALID_MESH', `${fieldPrefix}.positions`, 'mesh is empty');
  let indices: Uint32Array;
  if (input.indices === undefined) {
    if (vertexCount % 3 !== 0) fail('INVALID_MESH', `${fieldPrefix}.positions`, `without indices the vertex count (${vertexCount}) must be a multiple of 3`);
    indices = new Uint32Array(vertexCount);
    for (let i = 0; i < vertexCount; i++) indices[i] = i;
  } else {
    const raw = input.indices;
    if (!isArrayLike(raw)) fail('INVALID_MESH', `${fieldPrefix}.indices`, `expected an array of integers, got ${describe(raw)}`);
    if (raw.length === 0) fail('INVALID_MESH', `${fieldPrefix}.indices`, 'mesh has no triangles');
    if (raw.length % 3 !== 0) fail('INVALID_MESH', `${fieldPrefix}.indices`, `index count ${raw.length} is not a multiple of 3`);
    indices = new Uint32Array(raw.length);
    for (let i = 0; i < raw.length; i++) {
      const v = raw[i];
      if (typeof v !== 'number' || !Number.isInteger(v) || v < 0 || v >= vertexCount) {
        fail('INVALID_MESH', `${fieldPrefix}.indices[${i}]`, `index ${describe(v)} is out of range for ${vertexCount} vertices`);
      }
      indices[i] = v;
    }
  }
  const normals = stream(input.normals, `${fieldPrefix}.normals`, 3, vertexCount);
  const tangents = stream(input.tangents, `${fieldPrefix}.tangents`, 4, vertexCount);
  if (tangents) {
    for (let v = 0; v < vertexCount; v++) {
      const w = tangents[4 * v + 3]!;
      if (w !== 1 && w !== -1) fail('INVALID_MESH', `${fieldPrefix}.tangents[${4 * v + 3}]`, `the bitangent sign w must be 1 or -1, got ${w}`);
    }
  }
  const uvs = stream(input.uvs, `${fieldPrefix}.uvs`, 2, vertexCount);
  const uvs1 = stream(input.uvs1, `${fieldPrefix}.uvs1`, 2, vertexCount);
  const colors = colorsOf(input.colors, `${fieldPrefix}.colors`, vertexCount);
  let material: NormalizedMaterial | number;
  if (typeof input.material === 'number') {
    const count = context.materialCount ?? 0;
    if (!Number.isInteger(input.material) || input.material < 0 || input.material >= count) {
      fail('INVALID_MESH', `${fieldPrefix}.material`, `material index ${input.material} is out of range for ${count} materials`);
    }
    if (input.emission !== undefined) fail('INVALID_MESH', `${fieldPrefix}.emission`, 'mesh-level emission needs an inline material, not a shared material index');
    material = input.material;
  } else {
    material = normalizeMaterial(input.material, `${fieldPrefix}.material`, {
      textureCount: context.textureCount ?? 0,
      ...(input.emission !== undefined ? { meshEmission: input.emission } : {}),
      emissionField: `${fieldPrefix}.emission`,
      code: 'INVALID_MESH',
    });
  }
  const id = input.id ?? index;
  if (typeof id !== 'number' && typeof id !== 'string') fail('INVALID_MESH', `${fieldPrefix}.id`, 'expected a number or string');
  return { id, positions, indices, normals, tangents, uvs, uvs1, colors, material, vertexCount, triangleCount: indices.length / 3 };
}
