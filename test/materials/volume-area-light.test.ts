// Area lights (the `lights` option) seen from inside an absorbing KHR_materials_volume medium:
// Beer-Lambert absorption runs over the distance the path actually travels inside the medium up to
// the light, whether the light is reached by a BSDF sample (a closed box: the next surface lies
// beyond the light; an open volume: the ray escapes past the light) or by a next-event shadow ray.
// Index-matched (ior 1) interfaces make the delta transmission exact, so an orthographic camera
// looking at a rectangle light at depth d inside the medium sees L attenuationColor^(d / attenuationDistance).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import { validateAreaLight } from '../../src/lighting/area-lights.ts';
import type { WavefrontSceneLightInput } from '../../src/lighting/lighting-options.ts';
import type { WavefrontCameraInput, WavefrontMeshInput } from '../../src/scene/types.ts';
import { testDevice } from '../helpers/gpu.ts';
import { box } from './slab-scene.ts';

const SIZE = 12;
const color = [0.3, 0.6, 0.9];
const distance = 1.2;
const medium = { baseColorFactor: [1, 1, 1], metallicFactor: 0, roughnessFactor: 0, ior: 1, transmissionFactor: 1, thicknessFactor: 1, attenuationColor: color, attenuationDistance: distance };
/** The medium's front face: z = 1 (the camera looks down -z from z = 4). */
const FRONT = 1;

async function renderMean(meshes: WavefrontMeshInput[], lights: WavefrontSceneLightInput[], camera: WavefrontCameraInput, spp: number): Promise<number[]> {
  const device = await testDevice();
  const renderer = await createWavefrontPathTracingComputeRenderer({ device, width: SIZE, height: SIZE, maxDepth: 6, samplesPerPixel: spp, seed: 3, camera, meshes, lights });
  try {
    const stats = await renderer.renderFrame();
    assert.equal(stats.invalidSamples, 0);
    const { data } = await renderer.readRadiance();
    return [0, 1, 2].map((c) => {
      let sum = 0;
      for (let p = 0; p < SIZE * SIZE; p++) sum += data[4 * p + c]!;
      return sum / (SIZE * SIZE);
    });
  } finally {
    renderer.destroy();
  }
}

const frontCamera: WavefrontCameraInput = { type: 'orthographic', position: [0, 0, 4], target: [0, 0, 0], up: [0, 1, 0], orthographicHeight: 1 };
/** A rectangle light filling the view at z = lightZ, facing the camera. */
const rectangle = (z: number) => ({ type: 'rectangle' as const, center: [0, 0, z], edgeU: [3, 0, 0], edgeV: [0, 3, 0], emission: [1, 1, 1], intensity: 2 });

function assertAttenuated(image: number[], L: number, depth: number, label: string, t: { diagnostic: (s: string) => void }): void {
  for (let c = 0; c < 3; c++) {
    const expected = L * color[c]! ** (depth / distance);
    t.diagnostic(`${label}, channel ${c}: ${image[c]!.toFixed(5)} (expected ${expected.toFixed(5)})`);
    // Delta transmission and a delta camera: every sample is exact up to float rounding.
    assert.ok(Math.abs(image[c]! - expected) <= 1e-3 * expected, `${label} channel ${c}: ${image[c]} vs ${expected}`);
  }
}

test('a closed absorbing box: an area light inside is attenuated over the depth to the light, not to the back face', async (t) => {
  const lightZ = -0.5;
  const light = rectangle(lightZ);
  const L = validateAreaLight(light).radiance[1];
  const image = await renderMean([{ ...box(-2, FRONT), material: medium }], [light], frontCamera, 4);
  assertAttenuated(image, L, FRONT - lightZ, 'closed box', t);
});

test('an open volume (its front face only): a ray escaping past an area light is absorbed up to the light', async (t) => {
  const lightZ = -0.8;
  const light = rectangle(lightZ);
  const L = validateAreaLight(light).radiance[1];
  const face: WavefrontMeshInput = { positions: [-1, -1, FRONT, 1, -1, FRONT, 1, 1, FRONT, -1, 1, FRONT], indices: [0, 1, 2, 0, 2, 3], material: medium };
  const image = await renderMean([face], [light], frontCamera, 4);
  assertAttenuated(image, L, FRONT - lightZ, 'open volume', t);
});

// A Lambertian floor inside the box lit by a small sphere light inside it: its radiance is
// (albedo / pi) int L cos T(t(w)) dw over the sphere's cone, t(w) the distance to the sphere along w;
// both next-event shadow rays and BSDF samples reach the light (MIS), and the camera then sees the
// floor through the medium's depth to it.
test('next-event and BSDF-sampled light inside the medium: a floor lit by a sphere light matches the absorbed irradiance integral', async (t) => {
  const albedo = 0.8;
  const floorZ = -1.5;
  const sphere = { center: [0.5, 0, -1], radius: 0.1 };
  const light = { type: 'sphere' as const, center: sphere.center, radius: sphere.radius, emission: [1, 1, 1], intensity: 20 };
  const L = validateAreaLight(light).radiance[1];
  const floor: WavefrontMeshInput = {
    positions: [-0.9, -0.9, floorZ, 0.9, -0.9, floorZ, 0.9, 0.9, floorZ, -0.9, 0.9, floorZ],
    indices: [0, 1, 2, 0, 2, 3],
    material: { baseColorFactor: [albedo, albedo, albedo], metallicFactor: 0, roughnessFactor: 1, ior: 1 },
  };
  // The view (x in [-0.4, 0], y in [-0.2, 0.2]) sees the floor, not the light.
  const camera: WavefrontCameraInput = { type: 'orthographic', position: [-0.2, 0, 4], target: [-0.2, 0, 0], up: [0, 1, 0], orthographicHeight: 0.4 };
  const image = await renderMean([{ ...box(-2, FRONT), material: medium }, floor], [light], camera, 256);
  // Reference: quadrature over the cone (uniform in cos alpha and phi) at 4 x 4 points per pixel.
  const reference = [0, 0, 0];
  const n = 4 * SIZE;
  const steps = 48;
  for (let j = 0; j < n; j++) {
    for (let i = 0; i < n; i++) {
      const p = [-0.4 + (0.4 * (i + 0.5)) / n, -0.2 + (0.4 * (j + 0.5)) / n, floorZ];
      const D = sphere.center.map((v, k) => v - p[k]!);
      const dist = Math.hypot(D[0]!, D[1]!, D[2]!);
      const axis = D.map((v) => v / dist);
      const cosMax = Math.sqrt(1 - (sphere.radius / dist) ** 2);
      // An orthonormal frame around the axis.
      const helper = Math.abs(axis[0]!) < 0.9 ? [1, 0, 0] : [0, 1, 0];
      const u0 = [axis[1]! * helper[2]! - axis[2]! * helper[1]!, axis[2]! * helper[0]! - axis[0]! * helper[2]!, axis[0]! * helper[1]! - axis[1]! * helper[0]!];
      const ul = Math.hypot(u0[0]!, u0[1]!, u0[2]!);
      const u = u0.map((v) => v / ul);
      const v = [axis[1]! * u[2]! - axis[2]! * u[1]!, axis[2]! * u[0]! - axis[0]! * u[2]!, axis[0]! * u[1]! - axis[1]! * u[0]!];
      const sums = [0, 0, 0];
      for (let a = 0; a < steps; a++) {
        const cosA = 1 - ((a + 0.5) / steps) * (1 - cosMax);
        const sinA = Math.sqrt(1 - cosA * cosA);
        for (let b = 0; b < steps; b++) {
          const phi = (2 * Math.PI * (b + 0.5)) / steps;
          const w = [0, 1, 2].map((k) => cosA * axis[k]! + sinA * (Math.cos(phi) * u[k]! + Math.sin(phi) * v[k]!));
          // Nearest intersection with the sphere along w: t = dist cosA - sqrt(r^2 - dist^2 sin^2 A).
          const tHit = dist * cosA - Math.sqrt(Math.max(0, sphere.radius ** 2 - (dist * sinA) ** 2));
          for (let c = 0; c < 3; c++) sums[c]! += w[2]! * color[c]! ** (tHit / distance);
        }
      }
      const solidAngle = 2 * Math.PI * (1 - cosMax);
      for (let c = 0; c < 3; c++) reference[c]! += (albedo / Math.PI) * L * (sums[c]! / (steps * steps)) * solidAngle * color[c]! ** ((FRONT - floorZ) / distance);
    }
  }
  for (let c = 0; c < 3; c++) {
    const expected = reference[c]! / (n * n);
    t.diagnostic(`floor, channel ${c}: ${image[c]!.toFixed(5)} (expected ${expected.toFixed(5)})`);
    assert.ok(Math.abs(image[c]! - expected) <= 0.02 * expected, `floor channel ${c}: ${image[c]} vs ${expected}`);
  }
});
