import { describe, fail, isArrayLike } from '../errors/validate.ts';
import { maxCoordinateMagnitude } from './limits.ts';
import type { WavefrontInstanceInput } from './types.ts';

/** A validated placement: affine object-to-world rows and the inverse transpose for normals. */
export interface NormalizedInstance {
  id: number | string;
  mesh: number;
  /** Material index override, or null for the mesh's own material. */
  material: number | null;
  /** Rows of the 3x4 affine object-to-world matrix, row-major. */
  objectToWorld: readonly number[];
  /** Rows of the inverse transpose of the linear 3x3 part, row-major. */
  normalToWorld: readonly number[];
  /** Determinant of the linear part: negative for mirroring transforms (winding flips). */
  determinant: number;
}

export const identityTransform = Object.freeze([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]);

/** Affine rows from a column-major 4x4 (glTF), validating finiteness, affinity and invertibility. */
export function affineFromColumnMajor(m: ArrayLike<number>, field: string, code: 'INVALID_INSTANCE' | 'INVALID_OPTION' = 'INVALID_INSTANCE'): Pick<NormalizedInstance, 'objectToWorld' | 'normalToWorld' | 'determinant'> {
  if (!isArrayLike(m) || m.length !== 16) fail(code, field, `expected 16 numbers (a column-major 4x4 matrix), got ${describe(m)}`);
  for (let i = 0; i < 16; i++) {
    const v = m[i];
    if (typeof v !== 'number' || !Number.isFinite(v)) fail(code, `${field}[${i}]`, `expected a finite number, got ${describe(v)}`);
    if (Math.abs(v) > maxCoordinateMagnitude) fail(code, `${field}[${i}]`, `|${v}| exceeds the largest supported coordinate ${maxCoordinateMagnitude}`);
  }
  if (m[3] !== 0 || m[7] !== 0 || m[11] !== 0 || m[15] !== 1) fail(code, field, 'the matrix is not affine: its last row must be (0, 0, 0, 1)');
  // Row r, column c of the matrix is m[4c + r]. Plain locals and arrays (a Float64Array costs 15x
  // more to allocate): moving 10,000 placements per frame validates 10,000 matrices.
  const a00 = m[0]!, a10 = m[1]!, a20 = m[2]!, a01 = m[4]!, a11 = m[5]!, a21 = m[6]!, a02 = m[8]!, a12 = m[9]!, a22 = m[10]!;
  const objectToWorld = [a00, a01, a02, m[12]!, a10, a11, a12, m[13]!, a20, a21, a22, m[14]!];
  // Cofactors: inverse transpose of A = cof(A) / det(A).
  const c00 = a11 * a22 - a12 * a21;
  const c01 = a12 * a20 - a10 * a22;
  const c02 = a10 * a21 - a11 * a20;
  const c10 = a02 * a21 - a01 * a22;
  const c11 = a00 * a22 - a02 * a20;
  const c12 = a01 * a20 - a00 * a21;
  const c20 = a01 * a12 - a02 * a11;
  const c21 = a02 * a10 - a00 * a12;
  const c22 = a00 * a11 - a01 * a10;
  const determinant = a00 * c00 + a01 * c01 + a02 * c02;
  const scale = Math.max(Math.abs(a00), Math.abs(a01), Math.abs(a02), Math.abs(a10), Math.abs(a11), Math.abs(a12), Math.abs(a20), Math.abs(a21), Math.abs(a22));
  if (!(Math.abs(determinant) > 1e-12 * scale * scale * scale)) fail(code, field, 'the matrix is singular (it flattens the mesh)');
  const inv = 1 / determinant;
  const normalToWorld = [c00 * inv, c01 * inv, c02 * inv, c10 * inv, c11 * inv, c12 * inv, c20 * inv, c21 * inv, c22 * inv];
  return { objectToWorld, normalToWorld, determinant };
}

export function normalizeWavefrontInstance(input: WavefrontInstanceInput, index: number, counts: { meshes: number; materials: number }): NormalizedInstance {
  const field = `instances[${index}]`;
  if (typeof input !== 'object' || input === null) fail('INVALID_INSTANCE', field, `expected { mesh, transform?, material? }, got ${describe(input)}`);
  for (const key of Object.keys(input)) {
    if (!['id', 'mesh', 'transform', 'material'].includes(key)) fail('INVALID_INSTANCE', `${field}.${key}`, 'unknown instance key');
  }
  if (typeof input.mesh !== 'number' || !Number.isInteger(input.mesh) || input.mesh < 0 || input.mesh >= counts.meshes) {
    fail('INVALID_INSTANCE', `${field}.mesh`, `mesh index ${describe(input.mesh)} is out of range for ${counts.meshes} meshes`);
  }
  let material: number | null = null;
  if (input.material !== undefined) {
    if (typeof input.material !== 'number' || !Number.isInteger(input.material) || input.material < 0 || input.material >= counts.materials) {
      fail('INVALID_INSTANCE', `${field}.material`, `material index ${describe(input.material)} is out of range for ${counts.materials} materials`);
    }
    material = input.material;
  }
  const id = input.id ?? index;
  if (typeof id !== 'number' && typeof id !== 'string') fail('INVALID_INSTANCE', `${field}.id`, 'expected a number or string');
  return { id, mesh: input.mesh, material, ...affineFromColumnMajor(input.transform ?? identityTransform, `${field}.transform`) };
}
