import type { Accessor } from '@gltf-transform/core';
import type { GpuRendererErrorCode } from '../../errors/gpu-renderer-error.ts';
import { fail } from '../../errors/validate.ts';

const ELEMENT_SIZES: Record<string, number> = { SCALAR: 1, VEC2: 2, VEC3: 3, VEC4: 4, MAT2: 4, MAT3: 9, MAT4: 16 };

/**
 * Reads an accessor's elements as floats, decoding normalized integers (glTF 2.0 section 3.6.2.4)
 * and rejecting non-finite values with an error naming the element (`field[i]`).
 */
export function readFloatAccessor(
  accessor: Accessor,
  field: string,
  code: GpuRendererErrorCode,
  allowedTypes: readonly string[],
): Float64Array {
  const type = accessor.getType();
  if (!allowedTypes.includes(type)) fail(code, field, `expected an accessor of type ${allowedTypes.join(' or ')}, got ${type}`);
  const size = ELEMENT_SIZES[type] ?? 1;
  const count = accessor.getCount();
  if (accessor.getArray() === null) fail(code, field, 'accessor has no data');
  const out = new Float64Array(count * size);
  const element: number[] = new Array<number>(size).fill(0);
  for (let i = 0; i < count; i++) {
    accessor.getElement(i, element);
    for (let c = 0; c < size; c++) {
      const v = element[c];
      if (!Number.isFinite(v)) fail(code, `${field}[${i}]`, `element ${i} component ${c} is not finite (${v})`);
      out[i * size + c] = v;
    }
  }
  return out;
}

/** Reads an integer accessor (indices, JOINTS_n) as unsigned integers. */
export function readIndexAccessor(accessor: Accessor, field: string, code: GpuRendererErrorCode, allowedTypes: readonly string[]): Uint32Array {
  const type = accessor.getType();
  if (!allowedTypes.includes(type)) fail(code, field, `expected an accessor of type ${allowedTypes.join(' or ')}, got ${type}`);
  if (accessor.getNormalized()) fail(code, field, 'expected integer values, got a normalized accessor');
  const array = accessor.getArray();
  if (array === null) fail(code, field, 'accessor has no data');
  const out = new Uint32Array(array.length);
  for (let i = 0; i < array.length; i++) {
    const v = array[i];
    if (!Number.isInteger(v) || v < 0) fail(code, `${field}[${Math.floor(i / (ELEMENT_SIZES[type] ?? 1))}]`, `expected a non-negative integer, got ${v}`);
    out[i] = v;
  }
  return out;
}

export function elementSize(type: string): number {
  return ELEMENT_SIZES[type] ?? 1;
}
