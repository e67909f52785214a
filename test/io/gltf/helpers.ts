// Builders for glTF test assets, made in memory with @gltf-transform (no binary fixtures).
import assert from 'node:assert/strict';
import { NodeIO, type Accessor, type Buffer as GltfBuffer, type Document, type Material, type Mesh, type TypedArray } from '@gltf-transform/core';
import { ALL_EXTENSIONS } from '@gltf-transform/extensions';
import { GpuRendererError } from '../../../src/errors/gpu-renderer-error.ts';

export function createIO(dependencies: Record<string, unknown> = {}): NodeIO {
  return new NodeIO().registerExtensions(ALL_EXTENSIONS).registerDependencies(dependencies);
}

export async function toGlb(document: Document, dependencies: Record<string, unknown> = {}): Promise<Uint8Array> {
  return createIO(dependencies).writeBinary(document);
}

/** The asset as .gltf JSON bytes with its buffers and images inlined as data URIs. */
export async function toGltfJsonBytes(document: Document): Promise<Uint8Array> {
  const { json, resources } = await createIO().writeJSON(document);
  const inline = (uri: string | undefined): string | undefined => {
    if (uri === undefined) return undefined;
    return `data:application/octet-stream;base64,${Buffer.from(resources[uri]).toString('base64')}`;
  };
  for (const buffer of json.buffers ?? []) buffer.uri = inline(buffer.uri);
  for (const image of json.images ?? []) if (image.uri !== undefined) image.uri = inline(image.uri);
  return new TextEncoder().encode(JSON.stringify(json));
}

export function accessor(document: Document, buffer: GltfBuffer, type: 'SCALAR' | 'VEC2' | 'VEC3' | 'VEC4', array: Float32Array | Uint16Array | Uint32Array | Int16Array | Int8Array | Uint8Array, normalized = false): Accessor {
  return document.createAccessor().setType(type).setArray(array as TypedArray).setBuffer(buffer).setNormalized(normalized);
}

/** A unit quad in the xy plane (z = 0), facing +z, with uvs (v down), normals and indices. */
export function quadMesh(document: Document, buffer: GltfBuffer, material?: Material, name = 'quad'): Mesh {
  const positions = new Float32Array([0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0]);
  const normals = new Float32Array([0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1]);
  const uvs = new Float32Array([0, 1, 1, 1, 1, 0, 0, 0]);
  const primitive = document
    .createPrimitive()
    .setAttribute('POSITION', accessor(document, buffer, 'VEC3', positions))
    .setAttribute('NORMAL', accessor(document, buffer, 'VEC3', normals))
    .setAttribute('TEXCOORD_0', accessor(document, buffer, 'VEC2', uvs))
    .setIndices(accessor(document, buffer, 'SCALAR', new Uint16Array([0, 1, 2, 0, 2, 3])));
  if (material) primitive.setMaterial(material);
  return document.createMesh(name).addPrimitive(primitive);
}

/** Asserts `promise` rejects with a GpuRendererError of `code` naming `field` exactly. */
export async function rejectsWith(promise: Promise<unknown>, code: string, field: string, message?: RegExp): Promise<void> {
  await assert.rejects(promise, (error: unknown) => {
    assert.ok(error instanceof GpuRendererError, `expected a GpuRendererError, got ${String(error)}`);
    assert.equal(error.code, code, error.message);
    assert.equal(error.field, field, error.message);
    if (message) assert.match(error.message, message);
    return true;
  });
}

export function assertClose(actual: ArrayLike<number>, expected: ArrayLike<number>, tolerance: number, label = ''): void {
  assert.equal(actual.length, expected.length, `${label} length`);
  for (let i = 0; i < expected.length; i++) {
    assert.ok(Math.abs(actual[i] - expected[i]) <= tolerance, `${label}[${i}]: ${actual[i]} vs ${expected[i]} (tolerance ${tolerance})`);
  }
}

// Independent reference math: row-major 4x4 arrays built from first principles, then transposed to
// glTF's column-major order only for comparison.
export type RowMajor = number[][];

export function translationRows(t: readonly number[]): RowMajor {
  return [[1, 0, 0, t[0]], [0, 1, 0, t[1]], [0, 0, 1, t[2]], [0, 0, 0, 1]];
}

export function scaleRows(s: readonly number[]): RowMajor {
  return [[s[0], 0, 0, 0], [0, s[1], 0, 0], [0, 0, s[2], 0], [0, 0, 0, 1]];
}

/** Rotation by `angle` radians about the z axis (counter-clockwise seen from +z). */
export function rotationZRows(angle: number): RowMajor {
  const c = Math.cos(angle);
  const s = Math.sin(angle);
  return [[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]];
}

export function rotationXRows(angle: number): RowMajor {
  const c = Math.cos(angle);
  const s = Math.sin(angle);
  return [[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1]];
}

export function mulRows(...ms: RowMajor[]): RowMajor {
  return ms.reduce((a, b) => a.map((row, r) => b[0].map((_, c) => row.reduce((sum, _v, k) => sum + a[r][k] * b[k][c], 0))));
}

export function columnMajor(m: RowMajor): number[] {
  const out: number[] = [];
  for (let c = 0; c < 4; c++) for (let r = 0; r < 4; r++) out.push(m[r][c]);
  return out;
}

/** Quaternion (x, y, z, w) for a rotation of `angle` about unit `axis`. */
export function quat(axis: readonly number[], angle: number): [number, number, number, number] {
  const s = Math.sin(angle / 2);
  return [axis[0] * s, axis[1] * s, axis[2] * s, Math.cos(angle / 2)];
}
