// White-furnace checks of the raster shading: under a uniform environment of radiance L, a
// Lambertian sphere of albedo a (ior 1: no specular) shows a L, and a rough conductor with F0 = 1
// shows L (the split sum with Fdez-Aguera's multiple-scattering term conserves energy), whether the
// environment is the uniform colour or a uniform map prefiltered on the GPU (mip chain, specular
// prefilter, spherical-harmonics irradiance). Linear tone mapping, so pixels are sRGB(radiance).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { linearToSrgb } from '../../src/film/tone-mapping.ts';
import { createRasterRenderer, type RasterRendererOptions } from '../../src/raster/index.ts';
import type { WavefrontMaterialInput } from '../../src/scene/types.ts';
import { testDevice } from '../helpers/gpu.ts';
import { uvSphere } from './scenes.ts';

const L = [0.6, 0.45, 0.3];
const size = 24;

function uniformMap(width: number, height: number): { width: number; height: number; data: Float32Array } {
  const data = new Float32Array(width * height * 4);
  for (let i = 0; i < width * height; i++) data.set([...L, 1], 4 * i);
  return { width, height, data };
}

async function renderSphere(material: WavefrontMaterialInput, environment: Pick<RasterRendererOptions, 'environment' | 'environmentMap'>): Promise<{ center: number[]; corner: number[] }> {
  const renderer = await createRasterRenderer({
    device: await testDevice(),
    width: size,
    height: size,
    toneMapping: 'linear',
    shadow: false,
    camera: { position: [0, 0, 3], target: [0, 0, 0], fovYDegrees: 40 },
    meshes: [{ ...uvSphere(1, 24, 16), material }],
    ...environment,
  });
  await renderer.render();
  const pixels = await renderer.readPixels();
  renderer.destroy();
  const at = (x: number, y: number): number[] => Array.from(pixels.data.slice(4 * (y * size + x), 4 * (y * size + x) + 3));
  return { center: at(size / 2, size / 2), corner: at(0, 0) };
}

function expectPixel(actual: number[], radiance: number[], tolerance: number, label: string): void {
  const expected = radiance.map((c) => Math.round(linearToSrgb(c) * 255));
  for (let c = 0; c < 3; c++) assert.ok(Math.abs(actual[c]! - expected[c]!) <= tolerance, `${label} channel ${c}: ${actual[c]} vs ${expected[c]}`);
}

const lambertian = { baseColorFactor: [0.5, 0.5, 0.5, 1], metallicFactor: 0, roughnessFactor: 1, ior: 1 };
const conductor = { baseColorFactor: [1, 1, 1, 1], metallicFactor: 1, roughnessFactor: 0.6 };

test('uniform environment colour: Lambertian a L, rough F0 = 1 conductor L', async () => {
  const lam = await renderSphere(lambertian, { environment: { color: L } });
  expectPixel(lam.center, L.map((c) => 0.5 * c), 1, 'Lambertian centre');
  const metal = await renderSphere(conductor, { environment: { color: L } });
  expectPixel(metal.center, L, 1, 'conductor centre');
});

test('uniform environment map prefiltered on the GPU: the same radiances, and the background shows L', async () => {
  const map = uniformMap(64, 32);
  const lam = await renderSphere(lambertian, { environmentMap: map });
  expectPixel(lam.center, L.map((c) => 0.5 * c), 1, 'Lambertian centre');
  expectPixel(lam.corner, L, 1, 'background');
  const metal = await renderSphere(conductor, { environmentMap: map });
  expectPixel(metal.center, L, 1, 'conductor centre');
});

test('extensions under a uniform environment: ior-1 transmission passes L, a clearcoat over black reflects 0.04 L head-on', async () => {
  // KHR_materials_transmission with ior 1 and a white base: the refracted ray sees L, no Fresnel loss.
  const transmissive = await renderSphere({ baseColorFactor: [1, 1, 1, 1], metallicFactor: 0, roughnessFactor: 0, ior: 1, transmissionFactor: 1 }, { environment: { color: L } });
  expectPixel(transmissive.center, L, 1, 'transmission');
  // KHR_materials_clearcoat (f0 0.04, smooth) over a black base: at normal incidence the split sum is 0.04 L.
  const coated = await renderSphere({ baseColorFactor: [0, 0, 0, 1], metallicFactor: 0, roughnessFactor: 1, ior: 1, clearcoatFactor: 1, clearcoatRoughnessFactor: 0 }, { environment: { color: L } });
  expectPixel(coated.center, L.map((c) => 0.04 * c), 2, 'clearcoat');
});
