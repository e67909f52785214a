import { test } from 'node:test';
import { mat4d } from 'wgpu-matrix';
import { composeTrs } from '../../src/math/mat4.ts';
import { assertClose } from '../animation/helpers.ts';
import { rng } from '../helpers/random.ts';

test('composeTrs equals the product translation(t) x rotation(q) x scaling(s) built by wgpu-matrix', () => {
  const random = rng(7);
  for (let i = 0; i < 20; i++) {
    const t = [random() * 4 - 2, random() * 4 - 2, random() * 4 - 2];
    const raw = [random() - 0.5, random() - 0.5, random() - 0.5, random() - 0.5];
    const q = raw.map((v) => v / Math.hypot(...raw));
    const s = [0.2 + random(), -0.5 - random(), 0.1 + 2 * random()];
    const reference = mat4d.multiply(mat4d.multiply(mat4d.translation(t), mat4d.fromQuat(q)), mat4d.scaling(s));
    const out = new Float64Array(16);
    composeTrs(t, 0, q, 0, s, 0, out);
    assertClose(out, reference, 1e-12, `case ${i}`);
  }
});

test('composeTrs reads and writes at offsets: instance i of packed TRS arrays lands at 16 * i', () => {
  const random = rng(11);
  const t = Float32Array.from({ length: 9 }, () => random() * 2 - 1);
  const q = new Float32Array(12);
  for (let i = 0; i < 3; i++) {
    const raw = [random() - 0.5, random() - 0.5, random() - 0.5, random() - 0.5];
    q.set(raw.map((v) => v / Math.hypot(...raw)), 4 * i);
  }
  const s = Float32Array.from({ length: 9 }, () => 0.5 + random());
  const out = new Float64Array(48);
  for (let i = 0; i < 3; i++) composeTrs(t, 3 * i, q, 4 * i, s, 3 * i, out, 16 * i);
  for (let i = 0; i < 3; i++) {
    const one = new Float64Array(16);
    composeTrs(t.subarray(3 * i, 3 * i + 3), 0, q.subarray(4 * i, 4 * i + 4), 0, s.subarray(3 * i, 3 * i + 3), 0, one);
    assertClose(out.subarray(16 * i, 16 * i + 16), one, 0, `instance ${i}`);
  }
});
