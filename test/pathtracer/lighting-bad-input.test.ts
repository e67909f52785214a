// Bad lighting input at the public boundary: typed errors naming the field, raised while the options
// are validated (before any GPU work), so nothing half-renders.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createWavefrontPathTracingComputeRenderer, GpuRendererError } from '../../src/index.ts';
import { testDevice } from '../helpers/gpu.ts';

async function expectError(options: Record<string, unknown>, code: string, field: string): Promise<void> {
  const device = await testDevice();
  await assert.rejects(
    createWavefrontPathTracingComputeRenderer({ device, width: 8, height: 8, ...options } as never),
    (error: unknown) => {
      assert.ok(error instanceof GpuRendererError, `expected GpuRendererError, got ${String(error)}`);
      assert.equal(error.code, code, `${field}: ${error.message}`);
      assert.equal(error.field, field, error.message);
      assert.ok(error.message.startsWith(`${field}: `), 'the message names the field');
      return true;
    },
  );
}

const map = (data: Float32Array | Uint16Array, width = 2, height = 1): Record<string, unknown> => ({ environmentMap: { width, height, data } });

test('environment maps: non-finite or negative texels, sizes that do not match the data, bad parameters', async () => {
  const good = new Float32Array(8).fill(1);
  await expectError(map(Float32Array.from([1, 1, 1, 1, 1, Number.NaN, 1, 1])), 'INVALID_ENVIRONMENT', 'environmentMap.data[5]');
  await expectError(map(Float32Array.from([1, -2, 1, 1, 1, 1, 1, 1])), 'INVALID_ENVIRONMENT', 'environmentMap.data[1]');
  await expectError(map(Float32Array.from([1, 1, 1, 1, Infinity, 1, 1, 1])), 'INVALID_ENVIRONMENT', 'environmentMap.data[4]');
  // Half floats: 0x7c00 is +Infinity.
  await expectError(map(Uint16Array.from([0x3c00, 0x3c00, 0x7c00, 0, 0, 0, 0, 0])), 'INVALID_ENVIRONMENT', 'environmentMap.data[2]');
  await expectError(map(good, 3, 1), 'INVALID_ENVIRONMENT', 'environmentMap.data');
  await expectError(map(good, 2.5, 1), 'INVALID_ENVIRONMENT', 'environmentMap.width');
  await expectError({ environmentMap: { width: 2, height: 1, data: [1, 1, 1, 1, 1, 1, 1, 1] } }, 'INVALID_ENVIRONMENT', 'environmentMap.data');
  await expectError({ environmentMap: { width: 2, height: 1, data: good, intensity: -1 } }, 'INVALID_ENVIRONMENT', 'environmentMap.intensity');
  await expectError({ environmentMap: { width: 2, height: 1, data: good, intensity: 1e30 } }, 'INVALID_ENVIRONMENT', 'environmentMap.intensity');
  await expectError({ environmentMap: { width: 2, height: 1, data: good, rotationRadians: Number.NaN } }, 'INVALID_ENVIRONMENT', 'environmentMap.rotationRadians');
  await expectError({ environmentMap: { width: 2, height: 1, data: good }, environmentLighting: {} }, 'INVALID_OPTION', 'environmentLighting');
  await expectError({ environmentMap: { width: 2, height: 1, data: good }, environment: { color: [1, 1, 1] } }, 'INVALID_OPTION', 'environment');
});

test('environmentLighting: presets, sun, turbidity and albedo are checked', async () => {
  await expectError({ environmentLighting: { preset: 'mars' } }, 'INVALID_ENVIRONMENT', 'environmentLighting.preset');
  await expectError({ environmentLighting: { turbidity: 20 } }, 'INVALID_ENVIRONMENT', 'environmentLighting.turbidity');
  await expectError({ environmentLighting: { sunDirection: [0, -1, 0] } }, 'INVALID_ENVIRONMENT', 'environmentLighting.sunDirection');
  await expectError({ environmentLighting: { sunDirection: [0, Number.NaN, 1] } }, 'INVALID_ENVIRONMENT', 'environmentLighting.sunDirection[1]');
  await expectError({ environmentLighting: { sunColor: [1, -1, 1] } }, 'INVALID_ENVIRONMENT', 'environmentLighting.sunColor[1]');
  await expectError({ environmentLighting: { groundAlbedo: 2 } }, 'INVALID_ENVIRONMENT', 'environmentLighting.groundAlbedo');
  await expectError({ environmentLighting: { sunIntensity: 1e30 } }, 'INVALID_ENVIRONMENT', 'environmentLighting.sunIntensity[0]');
});

test('lights with non-finite or out-of-range parameters name the field', async () => {
  await expectError({ lights: [{ type: 'point', position: [0, Number.NaN, 0] }] }, 'INVALID_LIGHT', 'lights[0].position[1]');
  await expectError({ lights: [{ type: 'point', position: [0, 1, 0] }, { type: 'spot', position: [0, 1, 0], direction: [0, -1, 0], outerConeAngle: 3 }] }, 'INVALID_LIGHT', 'lights[1].outerConeAngle');
  await expectError({ lights: [{ type: 'directional', direction: [0, 0, 0] }] }, 'INVALID_LIGHT', 'lights[0].direction');
  await expectError({ lights: [{ type: 'point', position: [0, 1, 0], intensity: Infinity }] }, 'INVALID_LIGHT', 'lights[0].intensity');
  await expectError({ lights: [{ type: 'point', position: [0, 1, 0], intensity: 1e30 }] }, 'INVALID_LIGHT', 'lights[0].intensity[0]');
  await expectError({ lights: [{ type: 'point', position: [0, 1e19, 0] }] }, 'INVALID_LIGHT', 'lights[0].position[1]');
  await expectError({ lights: [{ type: 'laser' }] }, 'INVALID_LIGHT', 'lights[0].type');
  await expectError({ lights: [{ type: 'rectangle', center: [0, 1, 0], edgeU: [1, 0, 0], edgeV: [1, 0, 1] }] }, 'INVALID_LIGHT', 'lights[0].edgeV');
  await expectError({ lights: [{ type: 'sphere', center: [0, 1, 0], radius: -1 }] }, 'INVALID_LIGHT', 'lights[0].radius');
  await expectError({ lights: [{ type: 'disk', center: [0, 1, 0], normal: [0, -1, 0], radius: 1, emission: [1, Number.NaN, 1] }] }, 'INVALID_LIGHT', 'lights[0].emission[1]');
  await expectError({ lights: { type: 'point' } }, 'INVALID_LIGHT', 'lights');
});

test('portals, portal mode and light sampler', async () => {
  const env = { environment: { color: [1, 1, 1] } };
  await expectError({ ...env, environmentPortals: [{ center: [0, 1, 0], edgeU: [1, 0, 0], edgeV: [1, 1, 0] }] }, 'INVALID_ENVIRONMENT', 'environmentPortals[0].edgeV');
  await expectError({ ...env, environmentPortals: [{ center: [0, Number.NaN, 0], edgeU: [1, 0, 0], edgeV: [0, 1, 0] }] }, 'INVALID_ENVIRONMENT', 'environmentPortals[0].center[1]');
  await expectError({ environmentPortals: [{ center: [0, 1, 0], edgeU: [1, 0, 0], edgeV: [0, 1, 0] }] }, 'INVALID_ENVIRONMENT', 'environmentPortals');
  await expectError({ ...env, environmentPortalMode: 'gate' }, 'INVALID_ENVIRONMENT', 'environmentPortalMode');
  await expectError({ lightSampler: 'bvh' }, 'INVALID_OPTION', 'lightSampler');
});

test('misspelt keys are errors naming them, never ignored', async () => {
  await expectError({ environmentMap: { width: 1, height: 1, data: new Float32Array(4), rotation: 1 } }, 'INVALID_ENVIRONMENT', 'environmentMap.rotation');
  await expectError({ environmentLighting: { sunlitBaseline: 0.2 } }, 'INVALID_ENVIRONMENT', 'environmentLighting.sunlitBaseline');
  await expectError({ lights: [{ type: 'spot', position: [0, 1, 0], direction: [0, -1, 0], coneAngle: 0.5 }] }, 'INVALID_LIGHT', 'lights[0].coneAngle');
  await expectError({ lights: [{ type: 'sphere', center: [0, 1, 0], radius: 1, doubleSided: true }] }, 'INVALID_LIGHT', 'lights[0].doubleSided');
  await expectError({ environment: { color: [1, 1, 1] }, environmentPortals: [{ center: [0, 1, 0], edgeU: [1, 0, 0], edgeV: [0, 1, 0], size: 2 }] }, 'INVALID_ENVIRONMENT', 'environmentPortals[0].size');
});

test('after rejected lighting input the shared device renders lit scenes', async () => {
  const device = await testDevice();
  const renderer = await createWavefrontPathTracingComputeRenderer({
    device, width: 8, height: 8, camera: { position: [0, 0, 3], target: [0, 0, 0] },
    lights: [{ type: 'point', position: [0, 0, 2], intensity: 4 }],
    sceneObjects: [{ type: 'sphere', center: [0, 0, 0], radius: 1, color: [0.5, 0.5, 0.5], metallic: 0, roughness: 1, ior: 1 }],
  });
  try {
    const stats = await renderer.renderFrame();
    assert.equal(stats.invalidSamples, 0);
    const image = (await renderer.readRadiance()).data;
    assert.ok(image[4 * (4 * 8 + 4) + 1]! > 0);
  } finally {
    renderer.destroy();
  }
});
