import { fail, isArrayLike, describe } from '../errors/validate.ts';
import { normalizeMaterial, type NormalizedMaterial } from './material.ts';
import type { WavefrontMeshInput } from './types.ts';

/** A validated indexed triangle mesh in typed arrays. */
export interface NormalizedMesh {
  id: number | string;
  positions: Float32Array;
  indices: Uint32Array;
  normals: Float32Array | null;
  uvs: Float32Array | null;
  material: NormalizedMaterial;
  vertexCount: number;
  triangleCount: number;
}

function finiteArray(value: unknown, field: string, itemsPerVertex: number): Float32Array {
  if (!isArrayLike(value)) fail('INVALID_MESH', field, `expected an array of numbers, got ${describe(value)}`);
  if (value.length % itemsPerVertex !== 0) fail('INVALID_MESH', field, `length ${value.length} is not a multiple of ${itemsPerVertex}`);
  const out = new Float32Array(value.length);
  for (let i = 0; i < value.length; i++) {
    const v = value[i];
    if (typeof v !== 'number' || !Number.isFinite(v)) fail('INVALID_MESH', `${field}[${i}]`, `expected a finite number, got ${describe(v)}`);
    out[i] = v;
  }
  return out;
}

/**
 * Validates one mesh at the public boundary: finite attributes, consistent lengths, an index list
 * that is a multiple of 3 and in range. Errors name the field, e.g. `meshes[2].indices[5]`.
 */
export function normalizeWavefrontMesh(input: WavefrontMeshInput, index = 0, fieldPrefix = `meshes[${index}]`): NormalizedMesh {
  if (typeof input !== 'object' || input === null) fail('INVALID_MESH', fieldPrefix, 'expected a mesh object');
  const positions = finiteArray(input.positions, `${fieldPrefix}.positions`, 3);
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
  let normals: Float32Array | null = null;
  if (input.normals !== undefined) {
    normals = finiteArray(input.normals, `${fieldPrefix}.normals`, 3);
    if (normals.length !== positions.length) {
      fail('INVALID_MESH', `${fieldPrefix}.normals`, `has ${normals.length / 3} vertices but positions has ${vertexCount}`);
    }
  }
  let uvs: Float32Array | null = null;
  if (input.uvs !== undefined) {
    uvs = finiteArray(input.uvs, `${fieldPrefix}.uvs`, 2);
    if (uvs.length / 2 !== vertexCount) fail('INVALID_MESH', `${fieldPrefix}.uvs`, `has ${uvs.length / 2} vertices but positions has ${vertexCount}`);
  }
  const material = normalizeMaterial(input.material, `${fieldPrefix}.material`, input.emission);
  const id = input.id ?? index;
  if (typeof id !== 'number' && typeof id !== 'string') fail('INVALID_MESH', `${fieldPrefix}.id`, 'expected a number or string');
  return { id, positions, indices, normals, uvs, material, vertexCount, triangleCount: indices.length / 3 };
}
