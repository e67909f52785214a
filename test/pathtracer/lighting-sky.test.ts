// Sun and sky on the GPU against the CPU model: camera rays see the Hosek-Wilkie sky as the CPU
// evaluates it; the sun disc seen through a narrow camera integrates to its CPU irradiance (radiance
// x solid angle: size and brightness of the disc); and a horizontal Lambertian floor shows
// albedo / pi x the horizontal irradiance of sky and sun, with the sun cone-sampled and the sky
// map-sampled, each MIS-combined with BSDF sampling.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import { createWavefrontPathTracingComputeConfig } from '../../src/pathtracer/config.ts';
import { createWavefrontReferenceRay } from '../../src/pathtracer/reference.ts';
import { createEnvironmentLighting, clearSkyRadiance } from '../../src/lighting/environment-lighting.ts';
import { createHosekWilkieSky } from '../../src/lighting/hosek-wilkie.ts';
import { environmentRadiance } from '../../src/lighting/environment-map.ts';
import { sunSolidAngle } from '../../src/lighting/sun-light.ts';
import { normalize, type Vec3 } from '../../src/lighting/vec3.ts';
import { testDevice } from '../helpers/gpu.ts';
import { mapIrradiance } from '../lighting/gpu-fixtures.ts';

const sunDirection = normalize([0.5, Math.tan((40 * Math.PI) / 180) * Math.hypot(0.5, 0.6), 0.6]);
const sky = { preset: 'clear' as const, sunDirection, turbidity: 3, groundAlbedo: 0.3 };

test('camera rays see the clear sky of the CPU model (map lookup and Hosek-Wilkie itself)', async () => {
  const device = await testDevice();
  const size = 24;
  const camera = { position: [0, 0, 0], target: [-0.6, 0.5, -0.3], up: [0, 1, 0], fovYDegrees: 80 };
  const renderer = await createWavefrontPathTracingComputeRenderer({ device, width: size, height: size, samplesPerPixel: 16, seed: 2, camera, environmentLighting: sky });
  try {
    const stats = await renderer.renderFrame();
    assert.equal(stats.invalidSamples, 0);
    const image = (await renderer.readRadiance()).data;
    const lighting = createEnvironmentLighting(sky);
    const model = createHosekWilkieSky(3, [0.3, 0.3, 0.3], Math.asin(sunDirection[1]));
    const config = createWavefrontPathTracingComputeConfig({ width: size, height: size, camera });
    let compared = 0;
    for (let y = 0; y < size; y += 2) {
      for (let x = 0; x < size; x += 2) {
        const map = [0, 0, 0];
        const formula = [0, 0, 0];
        let above = true;
        for (let s = 0; s < 16; s++) {
          const ray = createWavefrontReferenceRay(config, { pixel: [x, y], jitter: [((s % 4) + 0.5) / 4, (Math.floor(s / 4) + 0.5) / 4] });
          if (ray.direction[1] < 0.05) above = false;
          const a = environmentRadiance(lighting.map, ray.direction);
          const b = clearSkyRadiance(model, sunDirection as Vec3, ray.direction);
          for (let c = 0; c < 3; c++) {
            map[c]! += a[c]! / 16;
            formula[c]! += b[c]! / 16;
          }
        }
        if (!above) continue;
        compared++;
        for (let c = 0; c < 3; c++) {
          const got = image[4 * (y * size + x) + c]!;
          assert.ok(Math.abs(got - map[c]!) < 0.01 * map[c]!, `pixel (${x}, ${y}) channel ${c}: ${got} vs map ${map[c]}`);
          // The baked map averages 2 x 2 model samples per texel: a few percent from the formula.
          assert.ok(Math.abs(got - formula[c]!) < 0.05 * formula[c]!, `pixel (${x}, ${y}) channel ${c}: ${got} vs Hosek-Wilkie ${formula[c]}`);
        }
      }
    }
    assert.ok(compared > 40);
  } finally {
    renderer.destroy();
  }
});

test('the sun disc seen by the camera: radiance x solid angle equals its CPU irradiance', async () => {
  const device = await testDevice();
  const size = 32;
  const fov = 2; // degrees: the 0.53 degree disc spans about 8 pixels
  const camera = { position: [0, 0, 0], target: sunDirection, up: [0, 1, 0], fovYDegrees: fov };
  const renderer = await createWavefrontPathTracingComputeRenderer({ device, width: size, height: size, samplesPerPixel: 64, seed: 4, camera, environmentLighting: sky });
  try {
    await renderer.renderFrame();
    const image = (await renderer.readRadiance()).data;
    const lighting = createEnvironmentLighting(sky);
    const sun = lighting.sun!;
    const config = createWavefrontPathTracingComputeConfig({ width: size, height: size, camera });
    // Integral of radiance over the image: sum of pixel means x each pixel's solid angle.
    let integral = 0;
    let skyIntegral = 0;
    for (let y = 0; y < size; y++) {
      for (let x = 0; x < size; x++) {
        const ray = createWavefrontReferenceRay(config, { pixel: [x, y], jitter: [0.5, 0.5] });
        const tan = Math.tan((fov * Math.PI) / 360);
        const pixel = (2 * tan) / size;
        const cos = normalize(ray.direction).reduce((a, d, i) => a + d * normalize(sunDirection)[i]!, 0);
        const omega = (pixel * pixel) * cos ** 3;
        integral += image[4 * (y * size + x) + 1]! * omega;
        skyIntegral += environmentRadiance(lighting.map, ray.direction)[1] * omega;
      }
    }
    const sunIrradiance = sun.radiance[1] * sunSolidAngle(sun);
    assert.ok(Math.abs(integral - skyIntegral - sunIrradiance) < 0.02 * sunIrradiance, `disc: ${integral - skyIntegral} vs ${sunIrradiance}`);
  } finally {
    renderer.destroy();
  }
});

test('a horizontal Lambertian floor under sun and sky shows albedo / pi x horizontal irradiance', async () => {
  const device = await testDevice();
  const size = 16;
  const albedo = 0.5;
  const camera = { type: 'orthographic' as const, position: [0, 5, 0], target: [0, 0, 0], up: [0, 0, -1], orthographicHeight: 2 };
  const renderer = await createWavefrontPathTracingComputeRenderer({
    device, width: size, height: size, samplesPerPixel: 128, seed: 8, maxDepth: 2, camera, environmentLighting: sky,
    meshes: [{ positions: [-50, 0, -50, 50, 0, -50, 50, 0, 50, -50, 0, 50], indices: [0, 2, 1, 0, 3, 2], material: { baseColorFactor: [albedo, albedo, albedo, 1], metallicFactor: 0, roughnessFactor: 1, ior: 1 } }],
  });
  try {
    const stats = await renderer.renderFrame();
    assert.equal(stats.invalidSamples, 0);
    const image = (await renderer.readRadiance()).data;
    const lighting = createEnvironmentLighting(sky);
    const sun = lighting.sun!;
    const skyE = mapIrradiance(lighting.map, Float64Array.from([0, 1, 0]), 2);
    for (let c = 0; c < 3; c++) {
      const e = skyE[c]! + sun.radiance[c]! * sunSolidAngle(sun) * sun.direction[1];
      let got = 0;
      for (let k = 0; k < size * size; k++) got += image[4 * k + c]! / (size * size);
      const want = (albedo / Math.PI) * e;
      assert.ok(Math.abs(got - want) < 0.01 * want, `channel ${c}: ${got} vs ${want}`);
    }
  } finally {
    renderer.destroy();
  }
});
