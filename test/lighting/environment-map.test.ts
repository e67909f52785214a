import { test } from 'node:test';
import assert from 'node:assert/strict';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { validateEnvironmentMap, bilinearTexel, environmentRadiance } from '../../src/lighting/environment-map.ts';
import { directionToEquirectUv, equirectUvToDirection, uvPdfToSolidAngle } from '../../src/lighting/equirect.ts';
import { cross, length, sub } from '../../src/lighting/vec3.ts';
import { rng, uniformSphere } from './helpers.ts';

function expectError(fn: () => unknown, field: string, code = 'INVALID_ENVIRONMENT'): GpuRendererError {
  try {
    fn();
  } catch (e) {
    assert.ok(e instanceof GpuRendererError, `expected GpuRendererError, got ${String(e)}`);
    assert.equal(e.code, code);
    assert.equal(e.field, field);
    return e;
  }
  assert.fail(`expected an error naming ${field}`);
}

test('validateEnvironmentMap returns float32 RGBA from float32 and half-float input', () => {
  const f = validateEnvironmentMap({ width: 2, height: 1, data: new Float32Array([1, 2, 3, 0.5, 0, 0.25, 4, 9]) });
  assert.deepEqual([...f.data], [1, 2, 3, 1, 0, 0.25, 4, 1]);
  assert.equal(f.intensity, 1);
  assert.equal(f.rotationRadians, 0);
  // binary16: 0x3c00 = 1, 0x4000 = 2, 0x3800 = 0.5, 0x7bff = 65504, 0x0001 = 2^-24.
  const h = validateEnvironmentMap({ width: 1, height: 2, data: new Uint16Array([0x3c00, 0x4000, 0x3800, 0, 0x7bff, 0x0001, 0, 0]), intensity: 2, rotationRadians: 1 });
  assert.deepEqual([...h.data], [1, 2, 0.5, 1, 65504, 2 ** -24, 0, 1]);
  assert.equal(h.intensity, 2);
  assert.equal(h.rotationRadians, 1);
});

test('validateEnvironmentMap rejects bad texels, sizes and types with the field named', () => {
  const data = new Float32Array(16).fill(1);
  data[9] = -0.5; // texel 2, channel G
  const e = expectError(() => validateEnvironmentMap({ width: 2, height: 2, data }), 'environmentMap.data[9]');
  assert.match(e.message, /texel 2 \(x 0, y 1\) channel G/);
  data[9] = Number.NaN;
  expectError(() => validateEnvironmentMap({ width: 2, height: 2, data }, 'scene.environmentMap'), 'scene.environmentMap.data[9]');
  // Half-float infinity (0x7c00) in channel B of texel 0.
  expectError(() => validateEnvironmentMap({ width: 1, height: 1, data: new Uint16Array([0, 0, 0x7c00, 0]) }), 'environmentMap.data[2]');
  expectError(() => validateEnvironmentMap({ width: 3, height: 2, data: new Float32Array(16) }), 'environmentMap.data');
  expectError(() => validateEnvironmentMap({ width: 2, height: 2, data: [1, 2, 3] }), 'environmentMap.data');
  expectError(() => validateEnvironmentMap({ width: 2, height: 2, data: new Float64Array(16) }), 'environmentMap.data');
  expectError(() => validateEnvironmentMap({ width: 0, height: 2, data: new Float32Array(0) }), 'environmentMap.width');
  expectError(() => validateEnvironmentMap({ width: 2.5, height: 2, data: new Float32Array(20) }), 'environmentMap.width');
  expectError(() => validateEnvironmentMap({ width: 2, height: 2, data: new Float32Array(16), intensity: -1 }), 'environmentMap.intensity');
  expectError(() => validateEnvironmentMap({ width: 2, height: 2, data: new Float32Array(16), rotationRadians: Infinity }), 'environmentMap.rotationRadians');
  expectError(() => validateEnvironmentMap(null), 'environmentMap');
});

test('equirect mapping: documented anchors, round trips and rotation', () => {
  const [u0, v0] = directionToEquirectUv([0, 1, 0]);
  assert.equal(v0, 0);
  assert.ok(Number.isFinite(u0));
  assert.equal(directionToEquirectUv([0, -1, 0])[1], 1);
  // atan2(z, x) = pi for -X: u = fract(0.5 + 0.5) = 0 (column 0 starts there); +X is u = 0.5.
  assert.deepEqual(directionToEquirectUv([-1, 0, 0]), [0, 0.5]);
  assert.deepEqual(directionToEquirectUv([1, 0, 0]), [0.5, 0.5]);
  assert.ok(Math.abs(directionToEquirectUv([0, 0, 1])[0] - 0.75) < 1e-15);
  // Rotating by r adds r / (2 pi) to u.
  assert.ok(Math.abs(directionToEquirectUv([1, 0, 0], Math.PI / 2)[0] - 0.75) < 1e-15);
  const random = rng(3);
  for (let k = 0; k < 1000; k++) {
    const d = uniformSphere(random);
    const rot = 4 * random() - 2;
    const [u, v] = directionToEquirectUv(d, rot);
    assert.ok(u >= 0 && u < 1 && v >= 0 && v <= 1);
    const back = equirectUvToDirection(u, v, rot);
    assert.ok(length(sub(back, d)) < 1e-12, `round trip ${d} -> ${back}`);
  }
});

test('equirect Jacobian: |dd/du x dd/dv| = 2 pi^2 sin(theta) by finite differences', () => {
  const random = rng(5);
  for (let k = 0; k < 200; k++) {
    const u = random();
    const v = 0.02 + 0.96 * random();
    const h = 1e-6;
    const du = sub(equirectUvToDirection(u + h, v), equirectUvToDirection(u - h, v)).map((x) => x / (2 * h));
    const dv = sub(equirectUvToDirection(u, v + h), equirectUvToDirection(u, v - h)).map((x) => x / (2 * h));
    const area = length(cross(du, dv));
    const sinTheta = Math.sin(Math.PI * v);
    assert.ok(Math.abs(area - 2 * Math.PI * Math.PI * sinTheta) < 1e-6 * area);
    // pdf_uv = 1 everywhere is the solid-angle density 1 / (2 pi^2 sin theta).
    assert.ok(Math.abs(uvPdfToSolidAngle(1, sinTheta) * area - 1) < 1e-6);
  }
});

test('bilinear lookup reproduces texel centres, wraps in u and clamps in v', () => {
  const map = validateEnvironmentMap({ width: 4, height: 2, data: new Float32Array([1, 0, 0, 1, 2, 0, 0, 1, 3, 0, 0, 1, 4, 0, 0, 1, 5, 0, 0, 1, 6, 0, 0, 1, 7, 0, 0, 1, 8, 0, 0, 1]), intensity: 3 });
  assert.equal(bilinearTexel(map, 0.125, 0.25)[0], 1);
  assert.equal(bilinearTexel(map, 0.875, 0.75)[0], 8);
  // Between the last and the first column (u = 0): half of each.
  assert.equal(bilinearTexel(map, 0, 0.25)[0], 2.5);
  // Above the first row centre: clamped to row 0.
  assert.equal(bilinearTexel(map, 0.375, 0)[0], 2);
  assert.equal(bilinearTexel(map, 0.375, 1)[0], 6);
  assert.equal(bilinearTexel(map, 0.375, 0.5)[0], 4);
  const d = equirectUvToDirection(0.125, 0.25);
  assert.ok(Math.abs(environmentRadiance(map, d)[0] - 3) < 1e-9);
});
