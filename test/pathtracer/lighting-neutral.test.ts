// The built-in neutral studio environment: its baked map integrates to the closed-form mean of its
// radiance function, and a white Lambertian sphere under it (a furnace with a non-uniform
// environment: nothing but the map lights it, every reflected ray escapes) renders albedo / pi x the
// irradiance from CPU quadrature of the map, so the map is sampled (NEE + MIS) like any other.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import { createNeutralEnvironment, neutralEnvironmentMeanRadiance, neutralEnvironmentRadiance } from '../../src/lighting/neutral-environment.ts';
import { environmentRadiance } from '../../src/lighting/environment-map.ts';
import { isGpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { testDevice } from '../helpers/gpu.ts';
import { assertSphereMatchesIrradiance, mapOption } from '../lighting/gpu-fixtures.ts';

test('the neutral environment map integrates to the closed-form mean; the closed form matches quadrature of the radiance function', () => {
  const mean = neutralEnvironmentMeanRadiance();
  for (const [w, h] of [[512, 256], [64, 32], [6, 2]] as const) {
    const map = createNeutralEnvironment({ width: w, height: h });
    let integral = 0;
    for (let j = 0; j < h; j++) {
      const solidAngle = ((2 * Math.PI) / w) * (Math.cos((Math.PI * j) / h) - Math.cos((Math.PI * (j + 1)) / h));
      for (let i = 0; i < w; i++) {
        const o = 4 * (j * w + i);
        assert.ok(map.data[o] === map.data[o + 1] && map.data[o] === map.data[o + 2], 'grey');
        integral += map.data[o]! * solidAngle;
      }
    }
    assert.ok(Math.abs(integral / (4 * Math.PI) - mean) < 1e-6 * mean, `${w} x ${h}: ${integral / (4 * Math.PI)} vs ${mean}`);
  }
  // Midpoint quadrature of the radiance function in (cos theta, phi), independent of the closed form.
  const n = 2000;
  let sum = 0;
  for (let a = 0; a < n; a++) {
    const y = -1 + (2 * (a + 0.5)) / n;
    const r = Math.sqrt(1 - y * y);
    for (let b = 0; b < n; b++) {
      const phi = (2 * Math.PI * (b + 0.5)) / n;
      sum += neutralEnvironmentRadiance([r * Math.cos(phi), y, r * Math.sin(phi)]);
    }
  }
  assert.ok(Math.abs(sum / (n * n) - mean) < 2e-3 * mean, `quadrature ${sum / (n * n)} vs closed form ${mean}`);
  assert.throws(() => createNeutralEnvironment({ height: 33 }), (e) => isGpuRendererError(e) && e.code === 'INVALID_ENVIRONMENT' && e.field === 'neutralEnvironment.height');
  assert.throws(() => createNeutralEnvironment({ size: 3 } as object), (e) => isGpuRendererError(e) && e.code === 'INVALID_ENVIRONMENT');
});

const size = 32;
/** Orthographic view of the unit sphere; pixel (x, y) centres lie at ((x + 0.5) / size * 2.4 - 1.2, ...). */
const half = 1.2;
const sphereCamera = { type: 'orthographic' as const, position: [0, 0, 5], target: [0, 0, 0], up: [0, 1, 0], orthographicHeight: 2 * half };

test('furnace: a white Lambertian sphere under the neutral environment renders 1 / pi x the CPU irradiance of the map', async () => {
  const device = await testDevice();
  const map = createNeutralEnvironment({ width: 128, height: 64 });
  const renderer = await createWavefrontPathTracingComputeRenderer({
    device, width: size, height: size, samplesPerPixel: 128, seed: 11, maxDepth: 2, camera: sphereCamera,
    environmentMap: mapOption(map),
    sceneObjects: [{ type: 'sphere', center: [0, 0, 0], radius: 1, color: [1, 1, 1], metallic: 0, roughness: 1, ior: 1 }],
  });
  try {
    const stats = await renderer.renderFrame();
    assert.equal(stats.invalidSamples, 0);
    const image = (await renderer.readRadiance()).data;
    // Every pixel off the sphere looks along -Z, straight at the map.
    const behind = environmentRadiance(map, [0, 0, -1])[0];
    for (let p = 0; p < size * size; p++) {
      const x = ((p % size) + 0.5) / size * 2 * half - half;
      const y = half - (Math.floor(p / size) + 0.5) / size * 2 * half;
      if (x * x + y * y > 1.25) assert.ok(Math.abs(image[4 * p]! - behind) < 1e-4 * behind, `background pixel ${p}: ${image[4 * p]} vs ${behind}`);
    }
    // The quadrants: the key, fill and rim softboxes light them differently.
    assertSphereMatchesIrradiance(image, map, { size, half, albedo: 1, meanTolerance: 0.01, blockTolerance: 0.03 });
  } finally {
    renderer.destroy();
  }
});
