import { test } from 'node:test';
import assert from 'node:assert/strict';
import {
  applyToneMapping,
  encodeRadianceToRgba8,
  linearToSrgb,
  toneMapAces,
  toneMapPbrNeutral,
} from '../../src/film/tone-mapping.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';

test('PBR Neutral: below the compression start colours only get the toe offset (a pure translation)', () => {
  // min >= 0.08 -> offset 0.04 exactly; peak after offset < 0.76 -> no compression.
  for (const c of [
    [0.1, 0.2, 0.3],
    [0.5, 0.08, 0.79],
    [0.18, 0.18, 0.18],
  ]) {
    const out = toneMapPbrNeutral(c);
    for (let i = 0; i < 3; i++) assert.ok(Math.abs(out[i] - (c[i] - 0.04)) < 1e-15, `${c} -> ${out}`);
  }
  // In the toe the offset is x - 6.25 x^2 where x is the smallest channel.
  const out = toneMapPbrNeutral([0.02, 0.3, 0.5]);
  const offset = 0.02 - 6.25 * 0.02 * 0.02;
  assert.deepEqual(out.map((v) => Number(v.toFixed(12))), [0.02 - offset, 0.3 - offset, 0.5 - offset].map((v) => Number(v.toFixed(12))));
  // Black stays black.
  assert.deepEqual(toneMapPbrNeutral([0, 0, 0]), [0, 0, 0]);
});

test('PBR Neutral: greys map monotonically into [0, 1) and are continuous at the compression start', () => {
  let prev = -1;
  for (let i = 0; i <= 4000; i++) {
    const x = Math.pow(10, -4 + (i / 4000) * 8); // 1e-4 .. 1e4
    const [r, g, b] = toneMapPbrNeutral([x, x, x]);
    assert.equal(r, g);
    assert.equal(g, b);
    assert.ok(r >= 0 && r < 1, `${x} -> ${r}`);
    assert.ok(r > prev, `not increasing at ${x}: ${prev} -> ${r}`);
    prev = r;
  }
  // Grey 0.8 is exactly the compression start (0.8 - 0.04 offset = 0.76): both branches give 0.76.
  const below = toneMapPbrNeutral([0.8 - 1e-9, 0.8 - 1e-9, 0.8 - 1e-9])[0];
  const above = toneMapPbrNeutral([0.8 + 1e-9, 0.8 + 1e-9, 0.8 + 1e-9])[0];
  assert.ok(Math.abs(below - 0.76) < 1e-8 && Math.abs(above - 0.76) < 1e-8);
  // Very bright colours desaturate towards white.
  const bright = toneMapPbrNeutral([1000, 10, 1]);
  assert.ok(bright[0] < 1 && bright[0] - bright[2] < 0.01, `${bright}`);
});

test('ACES (Hill fit): grey mid-points and bounds', () => {
  assert.deepEqual(toneMapAces([0, 0, 0]).map((v) => v < 1e-3), [true, true, true]);
  const big = toneMapAces([1e6, 1e6, 1e6]);
  assert.ok(big.every((v) => v === 1));
  let prev = -1;
  for (let i = 0; i <= 1000; i++) {
    const x = Math.pow(10, -3 + (i / 1000) * 6);
    const [r] = toneMapAces([x, x, x]);
    assert.ok(r >= prev && r <= 1, `${x} -> ${r}`);
    prev = r;
  }
  // Reference value of the fit for scene grey 0.18 (computed from the published constants).
  assert.ok(Math.abs(toneMapAces([0.18, 0.18, 0.18])[0] - 0.10559) < 1e-4);
});

test('applyToneMapping: linear clamps to [0, 1] only, negatives clamp to 0, unknown modes are typed errors', () => {
  assert.deepEqual(applyToneMapping([0.25, 2, -1], 'linear'), [0.25, 1, 0]);
  for (const mode of ['neutral', 'aces', 'linear'] as const) {
    const out = applyToneMapping([50, 0.5, 0.001], mode);
    assert.ok(out.every((v) => v >= 0 && v <= 1));
  }
  assert.throws(
    () => applyToneMapping([1, 1, 1], 'filmic' as never),
    (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_OPTION' && e.field === 'toneMapping',
  );
});

test('encodeRadianceToRgba8: exposure, tone mapping, sRGB and rounding', () => {
  const radiance = new Float32Array([0, 0, 0, 1, 0.5, 0.5, 0.5, 7, 100, 0.2, 0.0, 1, Number.NaN, 1, 2, 1]);
  const linear = encodeRadianceToRgba8(radiance, { toneMapping: 'linear', exposure: 1 });
  assert.deepEqual([...linear.slice(0, 4)], [0, 0, 0, 255]);
  assert.equal(linear[4], Math.floor(0.5 + 255 * linearToSrgb(0.5)));
  assert.equal(linear[7], 255);
  assert.deepEqual([...linear.slice(8, 12)], [255, Math.floor(0.5 + 255 * linearToSrgb(Math.fround(0.2))), 0, 255]);
  assert.deepEqual([...linear.slice(12, 16)], [0, 255, 255, 255]);
  // Exposure 2 on 0.5 is the same as 1.0.
  const exposed = encodeRadianceToRgba8(new Float32Array([0.5, 0.25, 0.125, 1]), { toneMapping: 'linear', exposure: 2 });
  assert.deepEqual([...exposed], [255, Math.floor(0.5 + 255 * linearToSrgb(0.5)), Math.floor(0.5 + 255 * linearToSrgb(0.25)), 255]);
  // Default is PBR Neutral.
  const neutral = encodeRadianceToRgba8(new Float32Array([0.18, 0.18, 0.18, 1]));
  assert.equal(neutral[0], Math.floor(0.5 + 255 * linearToSrgb(Math.fround(0.18) - 0.04)));
  assert.throws(() => encodeRadianceToRgba8(new Float32Array(3)), /multiple of 4/);
  assert.throws(() => encodeRadianceToRgba8(new Float32Array(4), { exposure: -1 }), /exposure/);
});
