import { test } from 'node:test';
import assert from 'node:assert/strict';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { readStruct } from '../../src/gpu-layout/struct-layout.ts';
import { validateLights } from '../../src/lighting/lights.ts';
import { buildEnvironmentSampler } from '../../src/lighting/environment-sampling.ts';
import { environmentMapUniformsLayout, packEnvironment } from '../../src/lighting/environment-tables.ts';
import { sunLightLayout } from '../../src/lighting/sun-light.ts';
import { makeMap } from './helpers.ts';

test('validateLights splits punctual and area lights and names the failing field', () => {
  const v = validateLights([
    { type: 'point', position: [0, 1, 0] },
    { type: 'sphere', center: [0, 0, 0], radius: 1 },
    { type: 'directional', direction: [0, -1, 0] },
  ]);
  assert.deepEqual(v.order, [
    { kind: 'punctual', index: 0 },
    { kind: 'area', index: 0 },
    { kind: 'punctual', index: 1 },
  ]);
  assert.equal(v.punctual[1]!.type, 'directional');
  assert.deepEqual(validateLights(undefined), { punctual: [], area: [], order: [] });
  const check = (input: unknown, field: string) =>
    assert.throws(() => validateLights(input), (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_LIGHT' && e.field === field);
  check([{ type: 'point', position: [0, 1, 0] }, { type: 'disk', center: [0, 0, 0], normal: [0, 1, 0], radius: Infinity }], 'lights[1].radius');
  check([{ type: 'laser' }], 'lights[0].type');
  check([null], 'lights[0].type');
  check({}, 'lights');
});

test('packEnvironment writes the uniforms and the sun record', () => {
  const sampler = buildEnvironmentSampler(makeMap(8, 4, (i) => [i, 1, 1], 2, Math.PI));
  const sun = { direction: [0, 1, 0] as [number, number, number], oneMinusCosThetaMax: 2e-5, radiance: [1, 2, 3] as [number, number, number], limbDarkening: true };
  const packed = packEnvironment(sampler, sun);
  const u = readStruct(environmentMapUniformsLayout, new DataView(packed.uniforms), 0);
  assert.deepEqual([u.width, u.height, u.intensity, u.rotationTurns, u.sampleable, u.sunEnabled], [8, 4, 2, 0.5, 1, 1]);
  const s = readStruct(sunLightLayout, new DataView(packed.sun), 0);
  assert.equal(s.limbDarkening, 1);
  assert.ok(Math.abs((s.oneMinusCosThetaMax as number) - 2e-5) < 1e-12);
  assert.equal(packed.entries, sampler.entries);
  const black = packEnvironment(buildEnvironmentSampler(makeMap(4, 2, () => [0, 0, 0])));
  assert.equal(readStruct(environmentMapUniformsLayout, new DataView(black.uniforms), 0).sampleable, 0);
});
