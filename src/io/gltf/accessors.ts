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
  const out = new Float32Array(source.length);
  const norm = accessor.getNormalized() ? NORMALIZATION[accessor.getComponentType()] : undefined;
  if (norm === undefined) {
    for (let i = 0; i < source.length; i++) out[i] = Number(source[i]);
  } else if (norm.signed) {
    for (let i = 0; i < source.length; i++) out[i] = Math.max(Number(source[i]) / norm.divisor, -1);
  } else {
    for (let i = 0; i < source.length; i++) out[i] = Number(source[i]) / norm.divisor;
  }
  return out;
}

export function accessorToUint32(accessor: Accessor): Uint32Array {
  const source = accessor.getArray();
  const out = new Uint32Array(accessor.getCount());
  if (source !== null) for (let i = 0; i < out.length; i++) out[i] = Number(source[i]);
  return out;
}

/** Index of the first non-finite component, or -1. */
export function firstNonFinite(values: Float32Array): number {
  for (let i = 0; i < values.length; i++) if (!Number.isFinite(values[i])) return i;
  return -1;
}
