import { test } from 'node:test';
import assert from 'node:assert/strict';
import type { AnimationSamplerData } from '../../src/animation/clips/clip-types.ts';
import { sampleAnimationSampler } from '../../src/animation/sampling/sample-sampler.ts';
import { readAnimatedModel } from '../../src/animation/model/read-model.ts';
import { axisAngleQuaternion, createRiggedFigure } from './fixtures/rigged-figure.ts';
import { assertClose, assertNear, assertSameRotation } from './helpers.ts';

function sampler(interpolation: AnimationSamplerData['interpolation'], input: number[], output: number[], components: number): AnimationSamplerData {
  return { interpolation, input: Float64Array.from(input), output: Float64Array.from(output), components };
}

function sample(s: AnimationSamplerData, t: number, rotation = false): number[] {
  const out = new Array<number>(s.components).fill(NaN);
  sampleAnimationSampler(s, t, rotation, out);
  return out;
}

test('LINEAR vectors: exact at keys, the average at midpoints, clamped outside the key range', () => {
  const s = sampler('LINEAR', [0.5, 1.5, 2], [1, 2, 3, 5, 0, -1, 7, 7, 7], 3);
  assertClose(sample(s, 0.5), [1, 2, 3], 0);
  assertClose(sample(s, 1.0), [3, 1, 1], 1e-15, 'midpoint of keys 0 and 1');
  assertClose(sample(s, 1.75), [6, 3.5, 3], 1e-15, 'midpoint of keys 1 and 2');
  assertClose(sample(s, 1.5 + 0.5 * 0.2), [5 + 2 * 0.2, 7 * 0.2, -1 + 8 * 0.2], 1e-12, '20% into the last interval');
  assertClose(sample(s, 0), [1, 2, 3], 0, 'before the first key');
  assertClose(sample(s, 9), [7, 7, 7], 0, 'after the last key');
});

test('STEP holds each key until the next one', () => {
  const s = sampler('STEP', [0, 1, 2], [10, 20, 30], 1);
  assert.equal(sample(s, 0)[0], 10);
  assert.equal(sample(s, 0.999)[0], 10);
  assert.equal(sample(s, 1)[0], 20);
  assert.equal(sample(s, 1.5)[0], 20);
  assert.equal(sample(s, 5)[0], 30);
});

test('LINEAR rotations slerp at constant angular speed (axis-angle reference), along the shorter arc', () => {
  const axis = [0.48, 0.6, 0.64] as const; // unit
  // 160 degrees apart: nlerp would be off by degrees here, slerp must match the axis-angle formula.
  const s = sampler('LINEAR', [0, 2], [...axisAngleQuaternion(axis, -40), ...axisAngleQuaternion(axis, 120)], 4);
  for (const u of [0, 0.1, 0.25, 0.5, 0.8, 1]) {
    const q = sample(s, 2 * u, true);
    assertSameRotation(q, axisAngleQuaternion(axis, -40 + 160 * u), 1e-12, `u = ${u}`);
    assertNear(Math.hypot(...q), 1, 1e-14, 'unit length');
  }
  // The same keys with the second quaternion negated (same rotation): the shorter arc is unchanged.
  const flipped = sampler('LINEAR', [0, 2], [...axisAngleQuaternion(axis, -40), ...axisAngleQuaternion(axis, 120).map((v) => -v)], 4);
  for (const u of [0.3, 0.7]) assertSameRotation(sample(flipped, 2 * u, true), axisAngleQuaternion(axis, -40 + 160 * u), 1e-12, `flipped u = ${u}`);
  // Equal keys: the nearly-parallel fallback returns the key itself.
  const still = sampler('LINEAR', [0, 1], [...axisAngleQuaternion(axis, 33), ...axisAngleQuaternion(axis, 33)], 4);
  assertSameRotation(sample(still, 0.4, true), axisAngleQuaternion(axis, 33), 1e-15, 'equal keys');
  // 300 degrees about the axis is -60 degrees the short way round.
  const long = sampler('LINEAR', [0, 1], [...axisAngleQuaternion(axis, 0), ...axisAngleQuaternion(axis, 300)], 4);
  assertSameRotation(sample(long, 0.5, true), axisAngleQuaternion(axis, -30), 1e-12, 'shorter arc');
});

test('CUBICSPLINE reproduces a cubic polynomial given its derivatives as tangents (Hermite identity)', () => {
  const f = (t: number): number => 2 * t ** 3 - t ** 2 + 3 * t - 1;
  const df = (t: number): number => 6 * t ** 2 - 2 * t + 3;
  const times = [0, 0.3, 1.1, 2];
  const output: number[] = [];
  // Per key: in-tangent, value, out-tangent. glTF tangents are per-second derivatives (the sampler scales them by t_d).
  for (const t of times) output.push(df(t), f(t), df(t));
  const s = sampler('CUBICSPLINE', times, output, 1);
  for (let t = 0; t <= 2; t += 0.05) assertNear(sample(s, t)[0], f(t), 1e-12, `t = ${t.toFixed(2)}`);
});

test('CUBICSPLINE end derivatives equal the out-tangent and the next in-tangent; in-tangents of the first key are ignored', () => {
  const s = sampler('CUBICSPLINE', [1, 3], [99, 0, 2, -4, 1, 99], 1);
  const h = 1e-6;
  assertNear(sample(s, 1)[0], 0, 0, 'value at the first key');
  assertNear(sample(s, 3)[0], 1, 0, 'value at the last key');
  assertNear((sample(s, 1 + h)[0] - sample(s, 1)[0]) / h, 2, 1e-5, 'derivative leaving key 0 = its out-tangent');
  assertNear((sample(s, 3)[0] - sample(s, 3 - h)[0]) / h, -4, 1e-5, 'derivative entering key 1 = its in-tangent');
  // Hermite basis partition of unity: with equal values and zero tangents the spline is constant.
  const flat = sampler('CUBICSPLINE', [0, 1], [0, 5, 0, 0, 5, 0], 1);
  for (const t of [0.1, 0.37, 0.9]) assertNear(sample(flat, t)[0], 5, 1e-14, 'constant');
});

test('CUBICSPLINE rotations come out normalised; the fixture spine channel matches a hand-evaluated Hermite spline', () => {
  const model = readAnimatedModel(createRiggedFigure().document);
  const spine = model.clips[0].channels.find((c) => c.path === 'rotation' && c.sampler.interpolation === 'CUBICSPLINE')!;
  const t = 0.2; // u = 0.4 of [0, 0.5]
  const u = 0.4;
  const td = 0.5;
  const v0 = axisAngleQuaternion([0, 1, 0], 10);
  const v1 = axisAngleQuaternion([0, 1, 0], 25);
  const b0 = [0, 0.2, 0, 0];
  const a1 = [0, 0.1, 0, 0];
  const h00 = 1 - 3 * u * u + 2 * u ** 3;
  const h10 = u - 2 * u * u + u ** 3;
  const h01 = 3 * u * u - 2 * u ** 3;
  const h11 = u ** 3 - u * u;
  const raw = [0, 1, 2, 3].map((i) => h00 * v0[i] + td * h10 * b0[i] + h01 * v1[i] + td * h11 * a1[i]);
  const length = Math.hypot(...raw);
  const q = sample(spine.sampler, t, true);
  assertClose(q, raw.map((v) => v / length), 1e-6, 'spine rotation');
  assertNear(Math.hypot(...q), 1, 1e-14, 'unit length');
});

test('weights channels interpolate every morph target component', () => {
  const s = sampler('LINEAR', [0, 1], [0, 1, 0.5, 1, 0, 0.5], 3);
  assertClose(sample(s, 0.25), [0.25, 0.75, 0.5], 1e-15);
  const single = sampler('LINEAR', [4], [0.3, 0.6], 2);
  assertClose(sample(single, 0), [0.3, 0.6], 0, 'one key: constant');
  assertClose(sample(single, 10), [0.3, 0.6], 0, 'one key: constant');
});
