/**
 * glTF accessor data as typed arrays: the one decoding of accessor elements, shared by the glTF
 * primitive reader (src/io/gltf/primitive), the scene loader (src/io/gltf) and src/animation's
 * skin and keyframe readers. Normalised integers decode with the glTF 2.0 formulas (section 3.11,
 * "Animations", and KHR_mesh_quantization: f = max(c / (2^(n-1) - 1), -1) for signed,
 * f = c / (2^n - 1) for unsigned); non-normalised integers (quantised positions, whose scale lives
 * in the node transform) convert as they are. Sparse accessors arrive already applied by the reader.
 */
import type { Accessor } from '@gltf-transform/core';
import type { GpuRendererErrorCode } from '../errors/gpu-renderer-error.ts';
import { fail } from '../errors/validate.ts';

const NORMALIZATION: Readonly<Record<number, { divisor: number; signed: boolean }>> = {
  5120: { divisor: 127, signed: true },
  5121: { divisor: 255, signed: false },
  5122: { divisor: 32767, signed: true },
  5123: { divisor: 65535, signed: false },
  5125: { divisor: 4294967295, signed: false },
};

const ELEMENT_SIZES: Readonly<Record<string, number>> = { SCALAR: 1, VEC2: 2, VEC3: 3, VEC4: 4, MAT2: 4, MAT3: 9, MAT4: 16 };

/** The accessor's components decoded into `out` (a new array of the accessor's length). */
function decodeInto<T extends Float32Array | Float64Array>(accessor: Accessor, out: T): T {
  const source = accessor.getArray();
  if (source === null) return out;
  const norm = accessor.getNormalized() ? NORMALIZATION[accessor.getComponentType()] : undefined;
  if (norm === undefined) {
    // The typed-array set converts natively, many times faster than an element loop on
    // million-vertex meshes.
    out.set(source);
  } else if (norm.signed) {
    for (let i = 0; i < source.length; i++) out[i] = Math.max(Number(source[i]) / norm.divisor, -1);
  } else {
    for (let i = 0; i < source.length; i++) out[i] = Number(source[i]) / norm.divisor;
  }
  return out;
}

/** The accessor's components as float32 (a copy: morph targets add into the result); zeros when it has no data. */
export function accessorToFloat32(accessor: Accessor): Float32Array {
  const source = accessor.getArray();
  return decodeInto(accessor, new Float32Array(source === null ? accessor.getCount() * accessor.getElementSize() : source.length));
}

export function accessorToUint32(accessor: Accessor): Uint32Array {
  const source = accessor.getArray();
  if (source === null) return new Uint32Array(accessor.getCount());
  return new Uint32Array(source.subarray(0, accessor.getCount()));
}

/** Index of the first non-finite component, or -1. */
export function firstNonFinite(values: Float32Array | Float64Array): number {
  // v - v is 0 for finite v and NaN for NaN and +-Infinity (one subtraction, no call per element).
  for (let i = 0; i < values.length; i++) {
    const v = values[i]!;
    if (v - v !== 0) return i;
  }
  return -1;
}

export function elementSize(type: string): number {
  return ELEMENT_SIZES[type] ?? 1;
}

/**
 * Reads an accessor's elements as float64, checking its type against `allowedTypes` and rejecting
 * a missing array or non-finite values with an error naming the element (`field[i]`).
 */
export function readFloatAccessor(accessor: Accessor, field: string, code: GpuRendererErrorCode, allowedTypes: readonly string[]): Float64Array {
  const type = accessor.getType();
  if (!allowedTypes.includes(type)) fail(code, field, `expected an accessor of type ${allowedTypes.join(' or ')}, got ${type}`);
  const size = elementSize(type);
  const source = accessor.getArray();
  if (source === null) fail(code, field, 'accessor has no data');
  const count = accessor.getCount();
  const out = decodeInto(accessor, new Float64Array(source.length)).subarray(0, count * size);
  const bad = firstNonFinite(out);
  if (bad >= 0) fail(code, `${field}[${Math.floor(bad / size)}]`, `element ${Math.floor(bad / size)} component ${bad % size} is not finite (${out[bad]})`);
  return out;
}
