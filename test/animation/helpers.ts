import assert from 'node:assert/strict';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';

/** Asserts |actual - expected| <= tolerance element-wise, naming the first mismatch. */
export function assertClose(actual: ArrayLike<number>, expected: ArrayLike<number>, tolerance: number, label = 'value'): void {
  assert.equal(actual.length, expected.length, `${label}: length`);
  for (let i = 0; i < expected.length; i++) {
    const diff = Math.abs(actual[i] - expected[i]);
    assert.ok(diff <= tolerance, `${label}[${i}]: ${actual[i]} vs ${expected[i]} (|diff| ${diff.toExponential(2)} > ${tolerance})`);
  }
}

export function assertNear(actual: number, expected: number, tolerance: number, label = 'value'): void {
  assert.ok(Math.abs(actual - expected) <= tolerance, `${label}: ${actual} vs ${expected} (tolerance ${tolerance})`);
}

/** Asserts that `fn` throws a GpuRendererError with this code and field. */
export function expectRendererError(fn: () => unknown, code: string, field: string, message?: RegExp, label = ''): void {
  const prefix = label === '' ? '' : `${label}: `;
  assert.throws(fn, (e: unknown) => {
    assert.ok(e instanceof GpuRendererError, `${prefix}expected a GpuRendererError, got ${String(e)}`);
    assert.equal(e.code, code, `${prefix}code of: ${e.message}`);
    assert.equal(e.field, field, `${prefix}field of: ${e.message}`);
    if (message) assert.match(e.message, message);
    return true;
  }, `${prefix}expected an error`);
}

/** Quaternions q and -q are the same rotation: compare up to sign. */
export function assertSameRotation(actual: ArrayLike<number>, expected: ArrayLike<number>, tolerance: number, label = 'rotation'): void {
  const dot = actual[0] * expected[0] + actual[1] * expected[1] + actual[2] * expected[2] + actual[3] * expected[3];
  const s = dot < 0 ? -1 : 1;
  assertClose(Array.from(actual, (v) => s * v), expected, tolerance, label);
}
