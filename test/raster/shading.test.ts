// Raster shading against analytic values: a base-colour texture shows its texels (sRGB decode,
// Lambertian under a unit uniform environment), a directional light gives a floor the radiance
// a E cos / pi, and the shadow map darkens exactly the floor under an occluder.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { linearToSrgb, srgbToLinear } from '../../src/film/tone-mapping.ts';
import { createRasterRenderer } from '../../src/raster/index.ts';
import { testDevice } from '../helpers/gpu.ts';
import { quad, uvSphere } from './scenes.ts';

test('a base colour texture shows its texels where they are projected', async () => {
  const size = 32;
  // 2 x 2 texels: red, green / blue, white (top row first).
  const texels = [200, 30, 30, 255, 30, 200, 30, 255, 30, 30, 200, 255, 230, 230, 230, 255];
  const renderer = await createRasterRenderer({
    device: await testDevice(),
    width: size,
    height: size,
    toneMapping: 'linear',
    shadow: false,
    environment: { color: [1, 1, 1] },
    camera: { type: 'orthographic', position: [0, 0, 2], target: [0, 0, 0], orthographicHeight: 2 },
    images: [{ width: 2, height: 2, data: new Uint8Array(texels) }],
    textures: [{ image: 0, sampler: { magFilter: 'nearest', minFilter: 'nearest' } }],
    meshes: [{ ...quad(1), material: { baseColorTexture: { index: 0 }, metallicFactor: 0, roughnessFactor: 1, ior: 1 } }],
  });
  await renderer.render();
  const pixels = await renderer.readPixels();
  renderer.destroy();
  const quadrants = [[8, 8, 0], [24, 8, 1], [8, 24, 2], [24, 24, 3]] as const;
  for (const [x, y, t] of quadrants) {
    for (let c = 0; c < 3; c++) {
      // Lambertian under unit radiance: the linear albedo, re-encoded.
      const expected = Math.round(linearToSrgb(srgbToLinear(texels[4 * t + c]! / 255)) * 255);
      const actual = pixels.data[4 * (y * size + x) + c]!;
      assert.ok(Math.abs(actual - expected) <= 1, `texel ${t} channel ${c} at (${x}, ${y}): ${actual} vs ${expected}`);
    }
  }
});

test('a directional light lights a floor with a E cos / pi and its shadow map hides the floor under an occluder', async () => {
  const size = 48;
  const albedo = 0.6;
  const E = 2;
  const floor = { positions: [-2, 0, 2, 2, 0, 2, 2, 0, -2, -2, 0, -2], normals: Array(4).fill([0, 1, 0]).flat(), indices: [0, 1, 2, 0, 2, 3] };
  const renderer = await createRasterRenderer({
    device: await testDevice(),
    width: size,
    height: size,
    toneMapping: 'linear',
    shadow: { mapSize: 512, bias: 0.002 },
    camera: { type: 'orthographic', position: [0, 5, 0], target: [0, 0, 0], up: [0, 0, -1], orthographicHeight: 4 },
    // Travels down and towards -x at 45 degrees: the sphere at (1, 1, 0) shadows the floor around the origin.
    lights: [{ type: 'directional', direction: [-1, -1, 0], intensity: E }],
    materials: [{ baseColorFactor: [albedo, albedo, albedo, 1], metallicFactor: 0, roughnessFactor: 1, ior: 1 }],
    meshes: [
      { ...floor, material: 0 },
      { ...uvSphere(0.5, 24, 12), material: 0 },
    ],
    instances: [{ mesh: 0 }, { mesh: 1, transform: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 1, 0, 1] }],
  });
  await renderer.render();
  const pixels = await renderer.readPixels();
  renderer.destroy();
  const at = (x: number, z: number): number => {
    // Orthographic top view: +x to the right, -z up; 4 m across the image.
    const px = Math.floor(((x + 2) / 4) * size);
    const py = Math.floor(((z + 2) / 4) * size);
    return pixels.data[4 * (py * size + px)]!;
  };
  const lit = Math.round(linearToSrgb((albedo * E * Math.SQRT1_2) / Math.PI) * 255);
  for (const [x, z] of [[-1.5, -1.5], [-1.5, 1.5], [0, 1.5], [1.8, -1.5]] as const) {
    assert.ok(Math.abs(at(x, z) - lit) <= 1, `lit floor at (${x}, ${z}): ${at(x, z)} vs ${lit}`);
  }
  // The umbra: the shadow of a sphere of radius 0.5 reaches 0.5 / cos 45 = 0.71 m along x and 0.5 m along z.
  for (const [x, z] of [[0, 0], [-0.3, 0], [0.3, 0], [0, 0.25], [0, -0.25]] as const) {
    assert.equal(at(x, z), 0, `shadowed floor at (${x}, ${z})`);
  }
});
