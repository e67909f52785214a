import assert from 'node:assert/strict';
import { test } from 'node:test';
import { linearToSrgb, srgbToLinear } from '../../src/color/srgb.ts';

test('sRGB curve: exact IEC 61966-2-1 breakpoints and values', () => {
  assert.equal(linearToSrgb(0), 0);
  assert.ok(Math.abs(linearToSrgb(1) - 1) < 1e-15);
  assert.ok(Math.abs(linearToSrgb(0.0031308) - 0.04045) < 1e-6);
  assert.equal(linearToSrgb(0.0031308), 0.0031308 * 12.92); // linear segment includes the breakpoint
  assert.ok(Math.abs(srgbToLinear(0.04045) - 0.0031308) < 1e-6);
  assert.equal(srgbToLinear(0.04045), 0.04045 / 12.92);
  // The power segment just above the breakpoint meets the linear one.
  assert.ok(Math.abs(linearToSrgb(0.0031308 + 1e-12) - 0.04045) < 1e-6);
  // Known value: 0.5 linear -> 0.735356983 sRGB; 0.5 sRGB -> 0.214041140 linear.
  assert.ok(Math.abs(linearToSrgb(0.5) - 0.735356983) < 1e-8);
  assert.ok(Math.abs(srgbToLinear(0.5) - 0.21404114) < 1e-8);
  // Not a 2.2 gamma: the toe is linear.
  assert.equal(linearToSrgb(0.001), 0.001 * 12.92);
});

test('sRGB round trip srgbToLinear(linearToSrgb(x)) == x', () => {
  for (let i = 0; i <= 100000; i++) {
    const x = i / 100000;
    assert.ok(Math.abs(srgbToLinear(linearToSrgb(x)) - x) <= 1e-15, `x = ${x}`);
  }
  for (let i = 0; i <= 255; i++) {
    const v = i / 255;
    assert.ok(Math.abs(linearToSrgb(srgbToLinear(v)) - v) <= 1e-15, `v = ${v}`);
  }
});
