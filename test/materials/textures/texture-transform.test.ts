import assert from 'node:assert/strict';
import { test } from 'node:test';
import { GpuRendererError } from '../../../src/errors/gpu-renderer-error.ts';
import { applyTextureTransform, textureTransformMatrix } from '../../../src/scene/texture-transform.ts';

const close = (a: readonly number[], b: readonly number[], label: string): void => {
  assert.equal(a.length, b.length);
  a.forEach((v, i) => assert.ok(Math.abs(v - b[i]!) < 1e-12, `${label}: [${a}] vs [${b}]`));
};

test('identity without a transform or with the defaults', () => {
  for (const t of [undefined, {}, { offset: [0, 0], rotation: 0, scale: [1, 1] }]) {
    const m = textureTransformMatrix(t);
    close([...m.transform0, ...m.transform1], [1, 0, 0, 0, 1, 0], 'identity');
  }
});

test("the extension's example: offset [0, 1], rotation pi/2, scale 0.5 shows the lower left quadrant", () => {
  // KHR_texture_transform, "Example JSON": "utilizes only the lower left quadrant of the source image,
  // rotated clockwise 90 degrees" (uv origin at the upper left, v down).
  const m = textureTransformMatrix({ offset: [0, 1], rotation: Math.PI / 2, scale: [0.5, 0.5] });
  close(applyTextureTransform(m, 0, 0), [0, 1], '(0,0)');
  close(applyTextureTransform(m, 1, 0), [0, 0.5], '(1,0)');
  close(applyTextureTransform(m, 0, 1), [0.5, 1], '(0,1)');
  close(applyTextureTransform(m, 1, 1), [0.5, 0.5], '(1,1)');
});

test('the T-axis inversion example maps v to 1 - v', () => {
  const m = textureTransformMatrix({ offset: [0, 1], scale: [1, -1] });
  close(applyTextureTransform(m, 0.3, 0.2), [0.3, 0.8], 'flip');
});

test('scale applies before rotation, offset last (T R S)', () => {
  const a = 0.7;
  const m = textureTransformMatrix({ offset: [0.25, -0.5], rotation: a, scale: [2, 3] });
  const [u, v] = [0.4, -0.9];
  // S, then R = [cos sin; -sin cos] (counter-clockwise with v pointing down), then T.
  const [su, sv] = [2 * u, 3 * v];
  close(applyTextureTransform(m, u, v), [Math.cos(a) * su + Math.sin(a) * sv + 0.25, -Math.sin(a) * su + Math.cos(a) * sv - 0.5], 'TRS');
  // The determinant is the area scale (what texture_lod uses).
  const det = m.transform0[0] * m.transform1[1] - m.transform0[1] * m.transform1[0];
  assert.ok(Math.abs(det - 6) < 1e-12);
});

test('bad transform values are INVALID_MATERIAL errors naming the field', () => {
  const field = 'materials[2].baseColorTexture.transform';
  for (const [t, at] of [
    [{ offset: [0, Number.NaN] }, `${field}.offset[1]`],
    [{ rotation: '1' }, `${field}.rotation`],
    [{ scale: [1] }, `${field}.scale`],
  ] as const) {
    assert.throws(
      () => textureTransformMatrix(t as never, field),
      (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_MATERIAL' && e.field === at,
    );
  }
});
