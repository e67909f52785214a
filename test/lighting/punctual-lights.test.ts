import { test } from 'node:test';
import assert from 'node:assert/strict';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { readStruct } from '../../src/gpu-layout/struct-layout.ts';
import {
  packPunctualLights,
  punctualLightIncident,
  punctualLightLayout,
  validatePunctualLight,
} from '../../src/lighting/punctual-lights.ts';

function expectField(fn: () => unknown, field: string): void {
  assert.throws(fn, (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_LIGHT' && e.field === field);
}

test('punctual lights: defaults and validation errors name the field', () => {
  const p = validatePunctualLight({ type: 'point', position: [1, 2, 3] });
  assert.deepEqual(p.intensity, [1, 1, 1]);
  assert.equal(p.range, Infinity);
  const s = validatePunctualLight({ type: 'spot', position: [0, 0, 0], direction: [0, 0, -2], color: [1, 0.5, 0], intensity: 4 });
  assert.deepEqual(s.direction, [0, 0, -1]);
  assert.deepEqual(s.intensity, [4, 2, 0]);
  assert.equal(s.innerConeAngle, 0);
  assert.equal(s.outerConeAngle, Math.PI / 4);
  expectField(() => validatePunctualLight({ type: 'area' }, 'lights[0]'), 'lights[0].type');
  expectField(() => validatePunctualLight({ type: 'point', position: [0, Number.NaN, 0] }, 'lights[1]'), 'lights[1].position[1]');
  expectField(() => validatePunctualLight({ type: 'point' }, 'lights[1]'), 'lights[1].position');
  expectField(() => validatePunctualLight({ type: 'point', position: [0, 0, 0], intensity: -1 }, 'l'), 'l.intensity');
  expectField(() => validatePunctualLight({ type: 'point', position: [0, 0, 0], intensity: Infinity }, 'l'), 'l.intensity');
  expectField(() => validatePunctualLight({ type: 'point', position: [0, 0, 0], color: [1, -1, 0] }, 'l'), 'l.color[1]');
  expectField(() => validatePunctualLight({ type: 'point', position: [0, 0, 0], range: 0 }, 'l'), 'l.range');
  expectField(() => validatePunctualLight({ type: 'directional', direction: [0, 0, 0] }, 'l'), 'l.direction');
  expectField(() => validatePunctualLight({ type: 'spot', position: [0, 0, 0], direction: [0, 1, 0], outerConeAngle: 2 }, 'l'), 'l.outerConeAngle');
  expectField(() => validatePunctualLight({ type: 'spot', position: [0, 0, 0], direction: [0, 1, 0], innerConeAngle: 0.5, outerConeAngle: 0.5 }, 'l'), 'l.innerConeAngle');
});

test('point light: inverse square law and the KHR range window', () => {
  const light = validatePunctualLight({ type: 'point', position: [0, 4, 0], intensity: 100, range: 8 });
  const at = (y: number) => punctualLightIncident(light, [0, y, 0]);
  const near = at(2); // distance 2 = range / 4
  assert.deepEqual(near.wi, [0, 1, 0]);
  assert.equal(near.distance, 2);
  assert.ok(Math.abs(near.incident[0] - (100 / 4) * (1 - 1 / 256)) < 1e-12);
  const half = at(0); // distance 4 = range / 2
  assert.ok(Math.abs(half.incident[1] - (100 / 16) * (1 - 1 / 16)) < 1e-12);
  assert.equal(at(-4.5).incident[2], 0); // beyond the range
  const unbounded = validatePunctualLight({ type: 'point', position: [0, 0, 0], intensity: 9 });
  assert.ok(Math.abs(punctualLightIncident(unbounded, [3, 0, 0]).incident[0] - 1) < 1e-15);
});

test('spot light: full inside the inner cone, zero outside the outer cone, squared smooth ramp between', () => {
  const inner = 0.2;
  const outer = 0.6;
  const light = validatePunctualLight({ type: 'spot', position: [0, 0, 0], direction: [0, -1, 0], intensity: 1, innerConeAngle: inner, outerConeAngle: outer });
  const atAngle = (a: number) => punctualLightIncident(light, [Math.sin(a), -Math.cos(a), 0]).incident[0];
  assert.ok(Math.abs(atAngle(0) - 1) < 1e-12);
  assert.ok(Math.abs(atAngle(0.19) - 1) < 1e-12);
  assert.equal(atAngle(0.61), 0);
  assert.equal(atAngle(Math.PI), 0);
  for (const a of [0.25, 0.4, 0.55]) {
    // KHR_lights_punctual: t = (cos a - cos outer) / (cos inner - cos outer), attenuation t^2.
    const t = (Math.cos(a) - Math.cos(outer)) / (Math.cos(inner) - Math.cos(outer));
    assert.ok(Math.abs(atAngle(a) - t * t) < 1e-12);
  }
});

test('directional light: constant illuminance towards -direction, unbounded shadow ray', () => {
  const light = validatePunctualLight({ type: 'directional', direction: [0, -1, 0], intensity: 3, color: [1, 2, 3] });
  const r = punctualLightIncident(light, [10, -50, 7]);
  assert.deepEqual(r.wi, [-0, 1, -0]);
  assert.equal(r.distance, Infinity);
  assert.deepEqual(r.incident, [3, 6, 9]);
});

test('punctual lights pack into 64-byte PunctualLight records', () => {
  assert.equal(punctualLightLayout.size, 64);
  const lights = [
    validatePunctualLight({ type: 'spot', position: [1, 2, 3], direction: [0, 0, -1], intensity: 2, range: 4, innerConeAngle: 0.1, outerConeAngle: 0.3 }),
    validatePunctualLight({ type: 'directional', direction: [0, -1, 0] }),
  ];
  const buffer = packPunctualLights(lights);
  assert.equal(buffer.byteLength, 128);
  const view = new DataView(buffer);
  const spot = readStruct(punctualLightLayout, view, 0);
  assert.equal(spot.kind, 1);
  assert.deepEqual(spot.position, [1, 2, 3]);
  assert.equal(spot.invRange, 0.25);
  const scale = 1 / (Math.cos(0.1) - Math.cos(0.3));
  assert.ok(Math.abs((spot.spotScale as number) - scale) < 1e-3 * scale);
  assert.ok(Math.abs((spot.spotOffset as number) + Math.cos(0.3) * scale) < 1e-3 * scale);
  const dir = readStruct(punctualLightLayout, view, 1);
  assert.equal(dir.kind, 2);
  assert.equal(dir.invRange, 0);
  assert.equal(packPunctualLights([]).byteLength, 64);
});
