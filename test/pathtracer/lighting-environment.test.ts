// Environment maps on the GPU: the WGSL sampler against the map's own distribution (chi-square over
// table cells) with sampled pdf = evaluated pdf = the CPU pdf; the lookup convention (u, v,
// rotation, intensity) seen by camera rays against the CPU reference; and a diffuse sphere inside
// an HDRI with a small sun converging to the value from CPU quadrature of the map.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import { createWavefrontPathTracingComputeConfig } from '../../src/pathtracer/config.ts';
import { createWavefrontReferenceRay } from '../../src/pathtracer/reference.ts';
import { environmentPdf } from '../../src/lighting/environment-sampling.ts';
import { environmentRadiance, type EnvironmentMap } from '../../src/lighting/environment-map.ts';
import { directionToEquirectUv } from '../../src/lighting/equirect.ts';
import { readBuffer, testDevice } from '../helpers/gpu.ts';
import { runTestProgram } from '../helpers/wgsl.ts';
import { BufferUsage } from '../../src/gpu/webgpu-constants.ts';
import { chiSquareTest } from '../lighting/helpers.ts';
import { assertSphereMatchesIrradiance, lightingFor, lightingResources, mapOption, testHdri } from '../lighting/gpu-fixtures.ts';

const samplerKernel = `
import package::lighting::environment_map::{sample_map, map_pdf, equirect_uv};
import package::shaders::lib::sampling::hash_u32;

@group(3) @binding(20) var<storage, read_write> out: array<vec4f>;

fn unit(x: u32) -> f32 { return f32(hash_u32(x) >> 8u) * (1.0 / 16777216.0); }

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) gid: vec3u) {
  let i = gid.x;
  let s = sample_map(vec2f(unit(2u * i + 0x9e37u), unit(2u * i + 1u + 0x9e37u)));
  out[2u * i] = vec4f(s.wi, s.pdf);
  out[2u * i + 1u] = vec4f(map_pdf(s.wi), equirect_uv(s.wi), 0.0);
}
`;

test('GPU environment sampling follows the map distribution (chi-square over table cells); sampled pdf = evaluated pdf = CPU pdf', async () => {
  const device = await testDevice();
  const map: EnvironmentMap = { ...testHdri(32, 16), rotationRadians: 0.7 };
  const lighting = lightingFor({ environment: { kind: 'map', map, sun: null, preset: null } });
  const sampler = lighting.environmentSampler!;
  const n = 1 << 18;
  const out = device.createBuffer({ size: n * 32, usage: BufferUsage.STORAGE | BufferUsage.COPY_SRC });
  await runTestProgram(device, { source: samplerKernel, resources: { ...lightingResources(device, lighting), out }, workgroups: n / 64 });
  const data = new Float32Array(await readBuffer(device, out));
  const { tableWidth: w, tableHeight: h } = sampler;
  const observed = new Float64Array(w * h);
  let total = 0;
  for (let k = 0; k < w * h; k++) total += sampler.weights[k]!;
  let mismatches = 0;
  for (let s = 0; s < n; s++) {
    const d = [data[8 * s]!, data[8 * s + 1]!, data[8 * s + 2]!];
    const pdf = data[8 * s + 3]!;
    assert.ok(pdf > 0 && Number.isFinite(pdf), `sample ${s}: pdf ${pdf}`);
    const [u, v] = directionToEquirectUv(d, map.rotationRadians);
    // Cells by the CPU's own mapping of the GPU direction: a convention mismatch shows as chi-square.
    observed[Math.min(h - 1, Math.floor(v * h)) * w + Math.min(w - 1, Math.floor(u * w))]! += 1;
    // A sample on a cell border may round into the neighbouring cell in f32: rare, counted.
    if (Math.abs(pdf - data[8 * s + 4]!) > 1e-3 * pdf || Math.abs(pdf - environmentPdf(sampler, d)) > 1e-3 * pdf) mismatches++;
  }
  const expected = Array.from(sampler.weights, (x) => (n * x) / total);
  const chi = chiSquareTest(observed, expected);
  assert.ok(!chi.outsideSupport, 'samples outside the support');
  assert.ok(chi.pValue > 1e-4, `chi-square ${chi.chi2.toFixed(1)} with ${chi.dof} dof, p = ${chi.pValue}`);
  assert.ok(mismatches < n * 1e-3, `${mismatches} of ${n} sampled pdfs differ from the evaluated or CPU pdf`);
});

const size = 32;

test('camera rays see the map with the documented convention, rotation and intensity', async () => {
  const device = await testDevice();
  // A smooth map (so a pixel's mean is its centre's value to high accuracy) with a distinct azimuth.
  const width = 64;
  const height = 32;
  const data = new Float32Array(width * height * 4);
  for (let j = 0; j < height; j++) {
    for (let i = 0; i < width; i++) {
      const u = (i + 0.5) / width;
      const v = (j + 0.5) / height;
      data.set([1 + 0.8 * Math.cos(2 * Math.PI * u), 1 + 0.8 * Math.sin(2 * Math.PI * u), 1 + 0.8 * Math.cos(Math.PI * v), 1], 4 * (j * width + i));
    }
  }
  const intensity = 1.7;
  const rotationRadians = 1.1;
  const camera = { position: [0, 0, 0], target: [1, 0.3, 0.4], up: [0, 1, 0], fovYDegrees: 70 };
  const renderer = await createWavefrontPathTracingComputeRenderer({
    device, width: size, height: size, samplesPerPixel: 16, seed: 1, camera, environmentMap: { width, height, data, intensity, rotationRadians },
  });
  try {
    const stats = await renderer.renderFrame();
    assert.equal(stats.invalidSamples, 0);
    const image = (await renderer.readRadiance()).data;
    const config = createWavefrontPathTracingComputeConfig({ width: size, height: size, camera });
    const map: EnvironmentMap = { width, height, data, intensity, rotationRadians };
    for (let y = 0; y < size; y += 3) {
      for (let x = 0; x < size; x += 3) {
        const want = [0, 0, 0];
        for (let s = 0; s < 16; s++) {
          const ray = createWavefrontReferenceRay(config, { pixel: [x, y], jitter: [((s % 4) + 0.5) / 4, (Math.floor(s / 4) + 0.5) / 4] });
          const L = environmentRadiance(map, ray.direction);
          for (let c = 0; c < 3; c++) want[c]! += L[c]! / 16;
        }
        for (let c = 0; c < 3; c++) {
          const got = image[4 * (y * size + x) + c]!;
          assert.ok(Math.abs(got - want[c]!) < 0.02 * want[c]! + 1e-3, `pixel (${x}, ${y}) channel ${c}: ${got} vs ${want[c]}`);
        }
      }
    }
  } finally {
    renderer.destroy();
  }
});

/** Orthographic view of the unit sphere; pixel (x, y) centres lie at ((x + 0.5) / size * 2.4 - 1.2, ...). */
const sphereCamera = { type: 'orthographic' as const, position: [0, 0, 5], target: [0, 0, 0], up: [0, 1, 0], orthographicHeight: 2.4 };

test('a diffuse sphere inside an HDRI with a small sun converges to CPU quadrature of the map', async () => {
  const device = await testDevice();
  const map = testHdri(64, 32);
  const albedo = 0.8;
  const renderer = await createWavefrontPathTracingComputeRenderer({
    device, width: size, height: size, samplesPerPixel: 128, seed: 5, maxDepth: 2, camera: sphereCamera,
    environmentMap: mapOption(map),
    sceneObjects: [{ type: 'sphere', center: [0, 0, 0], radius: 1, color: [albedo, albedo, albedo], metallic: 0, roughness: 1, ior: 1 }],
  });
  try {
    const stats = await renderer.renderFrame();
    assert.equal(stats.invalidSamples, 0);
    const image = (await renderer.readRadiance()).data;
    // The quadrants: the sun lights them very differently; 3% is about 4 standard errors at 128 spp.
    assertSphereMatchesIrradiance(image, map, { size, half: 1.2, albedo, meanTolerance: 0.01, blockTolerance: 0.03 });
  } finally {
    renderer.destroy();
  }
});
