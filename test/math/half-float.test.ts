import { test } from 'node:test';
import assert from 'node:assert/strict';
import { float32ToHalfBits, halfBitsToFloat32 } from '../../src/math/half-float.ts';
import { rng } from '../helpers/random.ts';

// Node 24's Float16Array (V8's IEEE binary16, round to nearest even) is the independent reference.
const reference = new Float16Array(1);
const referenceBits = new Uint16Array(reference.buffer);
function referenceHalfBits(v: number): number {
  reference[0] = v;
  return referenceBits[0];
}

test('every binary16 value decodes to its Float16Array value and re-encodes to the same bits', () => {
  for (let bits = 0; bits < 0x10000; bits++) {
    referenceBits[0] = bits;
    const value = halfBitsToFloat32(bits);
    if (Number.isNaN(reference[0])) {
      assert.ok(Number.isNaN(value));
      assert.ok(Number.isNaN(halfBitsToFloat32(float32ToHalfBits(value))));
      continue;
    }
    assert.equal(value, reference[0], `bits ${bits.toString(16)}`);
    assert.equal(float32ToHalfBits(value), bits, `bits ${bits.toString(16)}`);
  }
});

test('float32 -> half rounds to nearest even exactly as Float16Array does (random bit patterns and edge cases)', () => {
  const rand = rng(11);
  const f32 = new Float32Array(1);
  const u32 = new Uint32Array(f32.buffer);
  for (let i = 0; i < 300000; i++) {
    // Exponents concentrated around the half range so subnormals, overflow and ties all occur.
    u32[0] = ((rand() * 0x100000000) >>> 0 & 0x807fffff) | ((((rand() * 60) | 0) + 90) << 23);
    const v = f32[0];
    assert.equal(float32ToHalfBits(v), referenceHalfBits(v), `value ${v}`);
  }
  const edges = [0, -0, 65504, 65519.99, 65520, -65520, 1e6, Infinity, -Infinity, 2 ** -24, 2 ** -25, 3 * 2 ** -26, 2 ** -25 * 1.0001, 2 ** -14, 2 ** -14 - 2 ** -25, 1 + 2 ** -11, 1 + 3 * 2 ** -11];
  for (const v of edges) assert.equal(float32ToHalfBits(v), referenceHalfBits(v), `value ${v}`);
  assert.equal(float32ToHalfBits(65520), 0x7c00); // halfway to 2^16 rounds to even: infinity
  assert.equal(float32ToHalfBits(2 ** -25), 0); // halfway to the smallest subnormal rounds to 0
  assert.equal(float32ToHalfBits(-0), 0x8000);
  assert.ok(Number.isNaN(halfBitsToFloat32(float32ToHalfBits(Number.NaN))));
});
