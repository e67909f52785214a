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
  objectToWorld: Float64Array;
  /** Rows of the inverse transpose of the linear 3x3 part, row-major. */
  normalToWorld: Float64Array;
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
  // Row r, column c of the matrix is m[4c + r].
  const a = (r: number, c: number): number => m[4 * c + r]!;
  const objectToWorld = new Float64Array([a(0, 0), a(0, 1), a(0, 2), a(0, 3), a(1, 0), a(1, 1), a(1, 2), a(1, 3), a(2, 0), a(2, 1), a(2, 2), a(2, 3)]);
  // Cofactors: inverse transpose of A = cof(A) / det(A).
  const c00 = a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1);
  const c01 = a(1, 2) * a(2, 0) - a(1, 0) * a(2, 2);
  const c02 = a(1, 0) * a(2, 1) - a(1, 1) * a(2, 0);
  const c10 = a(0, 2) * a(2, 1) - a(0, 1) * a(2, 2);
  const c11 = a(0, 0) * a(2, 2) - a(0, 2) * a(2, 0);
  const c12 = a(0, 1) * a(2, 0) - a(0, 0) * a(2, 1);
  const c20 = a(0, 1) * a(1, 2) - a(0, 2) * a(1, 1);
  const c21 = a(0, 2) * a(1, 0) - a(0, 0) * a(1, 2);
  const c22 = a(0, 0) * a(1, 1) - a(0, 1) * a(1, 0);
  const determinant = a(0, 0) * c00 + a(0, 1) * c01 + a(0, 2) * c02;
  const scale = Math.max(...[0, 1, 2].flatMap((r) => [0, 1, 2].map((c) => Math.abs(a(r, c)))));
  if (!(Math.abs(determinant) > 1e-12 * scale * scale * scale)) fail(code, field, 'the matrix is singular (it flattens the mesh)');
  const inv = 1 / determinant;
  const normalToWorld = new Float64Array([c00 * inv, c01 * inv, c02 * inv, c10 * inv, c11 * inv, c12 * inv, c20 * inv, c21 * inv, c22 * inv]);
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
