/**
 * Accessor data as float32 or uint32 arrays. Normalised integers decode with the glTF 2.0 formulas
 * (section 3.11, "Animations", and KHR_mesh_quantization: f = max(c / (2^(n-1) - 1), -1) for signed,
 * f = c / (2^n - 1) for unsigned); non-normalised integers (quantised positions, whose scale lives in
 * the node transform) convert as they are. Sparse accessors arrive already applied by the reader.
 */
import type { Accessor } from '@gltf-transform/core';

const NORMALIZATION: Readonly<Record<number, { divisor: number; signed: boolean }>> = {
  5120: { divisor: 127, signed: true },
  5121: { divisor: 255, signed: false },
  5122: { divisor: 32767, signed: true },
  5123: { divisor: 65535, signed: false },
  5125: { divisor: 4294967295, signed: false },
};

export function accessorToFloat32(accessor: Accessor): Float32Array {
  const source = accessor.getArray();
  if (source === null) return new Float32Array(accessor.getCount() * accessor.getElementSize());
  const norm = accessor.getNormalized() ? NORMALIZATION[accessor.getComponentType()] : undefined;
  // A copy either way (morph targets add into the result): the typed-array constructor converts
  // natively, many times faster than an element loop on million-vertex meshes.
  if (norm === undefined) return new Float32Array(source);
  const out = new Float32Array(source.length);
  if (norm.signed) {
    for (let i = 0; i < source.length; i++) out[i] = Math.max(Number(source[i]) / norm.divisor, -1);
  } else {
    for (let i = 0; i < source.length; i++) out[i] = Number(source[i]) / norm.divisor;
  }
  return out;
}

export function accessorToUint32(accessor: Accessor): Uint32Array {
  const source = accessor.getArray();
  if (source === null) return new Uint32Array(accessor.getCount());
  return new Uint32Array(source.subarray(0, accessor.getCount()));
}

/** Index of the first non-finite component, or -1. */
export function firstNonFinite(values: Float32Array): number {
  // v - v is 0 for finite v and NaN for NaN and +-Infinity (one subtraction, no call per element).
  for (let i = 0; i < values.length; i++) {
    const v = values[i]!;
    if (v - v !== 0) return i;
  }
  return -1;
}
