// Punctual and area lights end to end: a Lambertian floor seen from above by an orthographic
// camera shows albedo / pi x irradiance, compared with analytic irradiance (inverse square law and
// the KHR_lights_punctual range and cone terms; Lambert's polygon formula for rectangles and disks;
// pi L (r / d)^2 cos for spheres). Area lights are opaque: pixels they cover show their emitting
// face or black, never the floor behind. glTF KHR_lights_punctual lights light the scene the same way.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { Document } from '@gltf-transform/core';
import { KHRLightsPunctual } from '@gltf-transform/extensions';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import { createWavefrontPathTracingComputeConfig } from '../../src/pathtracer/config.ts';
import { createWavefrontReferenceRay } from '../../src/pathtracer/reference.ts';
import { punctualLightIncident, validatePunctualLight } from '../../src/lighting/punctual-lights.ts';
import { intersectAreaLight } from '../../src/lighting/area-light-sampling.ts';
import { validateAreaLight, type AreaLight } from '../../src/lighting/area-lights.ts';
import { cross, dot, length, normalize, sub, type Vec3 } from '../../src/lighting/vec3.ts';
import { loadGltfScene } from '../../src/io/gltf/load-gltf-scene.ts';
import type { WavefrontSceneLightInput } from '../../src/lighting/lighting-options.ts';
import { testDevice } from '../helpers/gpu.ts';

const SIZE = 24;
const ALBEDO = 0.5;
const camera = { type: 'orthographic' as const, position: [0, 6, 0], target: [0, 0, 0], up: [0, 0, -1], orthographicHeight: 4 };
const floor = {
  positions: [-4, 0, -4, 4, 0, -4, 4, 0, 4, -4, 0, 4],
  indices: [0, 2, 1, 0, 3, 2],
  material: { baseColorFactor: [ALBEDO, ALBEDO, ALBEDO, 1], metallicFactor: 0, roughnessFactor: 1, ior: 1 },
};

async function render(lights: WavefrontSceneLightInput[], spp: number, extra: Record<string, unknown> = {}): Promise<Float32Array> {
  const device = await testDevice();
  const renderer = await createWavefrontPathTracingComputeRenderer({ device, width: SIZE, height: SIZE, samplesPerPixel: spp, seed: 11, maxDepth: 3, camera, meshes: [floor], lights, ...extra });
  try {
    const stats = await renderer.renderFrame();
    assert.equal(stats.invalidSamples, 0);
    return (await renderer.readRadiance()).data;
  } finally {
    renderer.destroy();
  }
}

/** Lambert's formula: irradiance at x (normal n) from a convex polygon of radiance 1 above its horizon. */
function polygonIrradiance(x: Vec3, n: Vec3, vertices: Vec3[]): number {
  let sum = 0;
  for (let i = 0; i < vertices.length; i++) {
    const a = normalize(sub(vertices[i]!, x));
    const b = normalize(sub(vertices[(i + 1) % vertices.length]!, x));
    const c = cross(a, b);
    const l = length(c);
    if (l === 0) continue;
    sum += Math.atan2(l, dot(a, b)) * (dot(n, c) / l);
  }
  return Math.abs(sum) / 2;
}

function areaLightIrradiance(l: AreaLight, x: Vec3, n: Vec3): number {
  const L = l.radiance[1];
  if (l.type === 'sphere') {
    const d = sub(l.center, x);
    const dist = length(d);
    return L * Math.PI * (l.radius / dist) ** 2 * dot(n, normalize(d));
  }
  const side = dot(sub(x, l.center), l.normal);
  if (!(side > 0 || (l.twoSided && side < 0))) return 0;
  let vertices: Vec3[];
  if (l.type === 'rectangle') {
    const c = l.center;
    const [u, v] = [l.edgeU, l.edgeV];
    vertices = [[-1, -1], [1, -1], [1, 1], [-1, 1]].map(([a, b]) => [c[0] + (a! * u[0] + b! * v[0]) / 2, c[1] + (a! * u[1] + b! * v[1]) / 2, c[2] + (a! * u[2] + b! * v[2]) / 2] as Vec3);
  } else {
    vertices = Array.from({ length: 512 }, (_, k) => {
      const phi = (2 * Math.PI * k) / 512;
      const a = Math.cos(phi) * l.radius;
      const b = Math.sin(phi) * l.radius;
      return [l.center[0] + a * l.edgeU[0] + b * l.edgeV[0], l.center[1] + a * l.edgeU[1] + b * l.edgeV[1], l.center[2] + a * l.edgeU[2] + b * l.edgeV[2]] as Vec3;
    });
  }
  return L * polygonIrradiance(x, n, vertices);
}

interface Expected {
  /** Expected green radiance of each pixel, or NaN where the pixel is partly covered by a light. */
  values: Float64Array;
}

/** Pixel means over 4 x 4 camera rays: the floor's albedo / pi x E, or the light a ray meets first. */
function expectedImage(irradiance: (x: Vec3) => number, areaLights: AreaLight[] = []): Expected {
  const config = createWavefrontPathTracingComputeConfig({ width: SIZE, height: SIZE, camera });
  const values = new Float64Array(SIZE * SIZE);
  for (let y = 0; y < SIZE; y++) {
    for (let x = 0; x < SIZE; x++) {
      let sum = 0;
      let covered = 0;
      for (let s = 0; s < 16; s++) {
        const ray = createWavefrontReferenceRay(config, { pixel: [x, y], jitter: [((s % 4) + 0.5) / 4, (Math.floor(s / 4) + 0.5) / 4] });
        const t = -ray.origin[1] / ray.direction[1];
        const hitLight = areaLights.map((l) => intersectAreaLight(l, ray.origin, ray.direction)).find((h) => h !== null && h.distance < t);
        if (hitLight) {
          covered++;
          sum += hitLight.radiance[1];
        } else {
          const p: Vec3 = [ray.origin[0] + t * ray.direction[0], 0, ray.origin[2] + t * ray.direction[2]];
          sum += (ALBEDO / Math.PI) * irradiance(p);
        }
      }
      values[y * SIZE + x] = covered > 0 && covered < 16 ? Number.NaN : sum / 16;
    }
  }
  return { values };
}

/** Compares 4 x 4 pixel blocks (or single pixels with block = 1) within a relative tolerance. */
function assertImage(image: Float32Array, expected: Expected, tolerance: number, what: string, block = 4): void {
  let compared = 0;
  // Where the irradiance has a kink inside a pixel (range and cone edges), 4 x 4 rays per pixel
  // approximate its mean only to about 1% of the image's brightest value.
  let brightest = 0;
  for (const v of expected.values) if (v > brightest) brightest = v;
  const slack = 0.01 * brightest * block * block;
  for (let by = 0; by < SIZE; by += block) {
    for (let bx = 0; bx < SIZE; bx += block) {
      let got = 0;
      let want = 0;
      let skip = false;
      for (let y = by; y < by + block; y++) {
        for (let x = bx; x < bx + block; x++) {
          const e = expected.values[y * SIZE + x]!;
          if (Number.isNaN(e)) skip = true;
          got += image[4 * (y * SIZE + x) + 1]!;
          want += e;
        }
      }
      if (skip) continue;
      compared++;
      assert.ok(Math.abs(got - want) <= tolerance * want + slack, `${what}: block (${bx}, ${by}): ${got / block / block} vs ${want / block / block}`);
    }
  }
  assert.ok(compared >= (SIZE / block) ** 2 / 2, `${what}: only ${compared} blocks compared`);
}

const up: Vec3 = [0, 1, 0];

test('point light: inverse square law and the range window (delta light in NEE, exact to float precision)', async () => {
  const input = { type: 'point' as const, position: [0.3, 1.2, -0.4], color: [1, 1, 1], intensity: 5, range: 3 };
  const light = validatePunctualLight(input);
  const image = await render([input], 16);
  const expected = expectedImage((p) => {
    const inc = punctualLightIncident(light, p);
    return inc.incident[1] * Math.max(0, dot(inc.wi, up));
  });
  assertImage(image, expected, 0.01, 'point', 1);
});

test('spot light: full inside the inner cone, squared smooth falloff to the outer cone', async () => {
  const input = { type: 'spot' as const, position: [-0.2, 1.5, 0.1], direction: [0.3, -1, 0.2], intensity: 8, innerConeAngle: 0.3, outerConeAngle: 0.6 };
  const light = validatePunctualLight(input);
  const image = await render([input], 16);
  const expected = expectedImage((p) => {
    const inc = punctualLightIncident(light, p);
    return inc.incident[1] * Math.max(0, dot(inc.wi, up));
  });
  assertImage(image, expected, 0.01, 'spot', 1);
});

test('directional light: illuminance times cos, with a point light beside it', async () => {
  const sun = { type: 'directional' as const, direction: [0.5, -1, 0.3], intensity: 2, color: [1, 0.8, 0.6] };
  const bulb = { type: 'point' as const, position: [1, 0.8, 1], intensity: 1 };
  const [ls, lb] = [validatePunctualLight(sun), validatePunctualLight(bulb)];
  const image = await render([sun, bulb], 64);
  const expected = expectedImage((p) =>
    [ls, lb].reduce((e, l) => {
      const inc = punctualLightIncident(l, p);
      return e + inc.incident[1] * Math.max(0, dot(inc.wi, up));
    }, 0),
  );
  // Two delta lights picked at random: the selection makes the estimate noisy.
  assertImage(image, expected, 0.03, 'directional + point');
});

test('rectangle light (one-sided, facing down): Lambert polygon irradiance; its back hides the floor', async () => {
  const input = { type: 'rectangle' as const, center: [0.2, 0.8, 0], edgeU: [0.8, 0, 0], edgeV: [0, 0, 0.6], emission: [1, 1, 1], intensity: 4 };
  const light = validateAreaLight(input);
  assert.ok(light.normal[1] < -0.99, 'the test light faces the floor');
  const image = await render([input], 128);
  const expected = expectedImage((p) => areaLightIrradiance(light, p, up), [light]);
  assertImage(image, expected, 0.03, 'rectangle');
  // Fully covered pixels see the light's non-emitting back face: exactly black.
  let black = 0;
  for (let k = 0; k < SIZE * SIZE; k++) {
    if (expected.values[k] === 0) {
      assert.equal(image[4 * k + 1], 0, `pixel ${k} behind the light`);
      black++;
    }
  }
  assert.ok(black > 4);
});

test('rectangle light facing away: dark floor one-sided, the same as facing down when two-sided', async () => {
  const away = { type: 'rectangle' as const, center: [0.2, 0.8, 0], edgeU: [0, 0, 0.6], edgeV: [0.8, 0, 0], intensity: 4 };
  assert.ok(validateAreaLight(away).normal[1] > 0.99);
  const oneSided = await render([away], 16);
  let sum = 0;
  for (let k = 0; k < SIZE * SIZE; k++) sum += oneSided[4 * k + 1]!;
  // The floor is dark; only pixels covered by the light's emitting face (seen from above) are lit.
  const light = validateAreaLight({ ...away, twoSided: true });
  const expectedOne = expectedImage(() => 0, [validateAreaLight(away)]);
  let want = 0;
  for (let k = 0; k < SIZE * SIZE; k++) if (!Number.isNaN(expectedOne.values[k]!)) want += expectedOne.values[k]!;
  assert.ok(want > 0 && sum >= want * 0.99, `one-sided: ${sum} vs covered pixels ${want}`);
  const twoSided = await render([{ ...away, twoSided: true }], 128);
  assertImage(twoSided, expectedImage((p) => areaLightIrradiance(light, p, up), [light]), 0.03, 'two-sided rectangle');
});

test('disk and sphere lights: solid-angle and area sampling match analytic irradiance', async () => {
  const disk = { type: 'disk' as const, center: [-0.3, 1, 0.2], normal: [0.2, -1, 0], radius: 0.4, intensity: 3 };
  const sphere = { type: 'sphere' as const, center: [0.6, 0.9, -0.5], radius: 0.25, emission: [1, 1, 1], intensity: 5 };
  const lights = [validateAreaLight(disk), validateAreaLight(sphere)];
  const image = await render([disk, sphere], 128);
  const expected = expectedImage((p) => lights.reduce((e, l) => e + areaLightIrradiance(l, p, up), 0), lights);
  assertImage(image, expected, 0.03, 'disk + sphere');
});

test('glTF KHR_lights_punctual lights light the scene like the same `lights` entries', async () => {
  const doc = new Document();
  const buffer = doc.createBuffer();
  const ext = doc.createExtension(KHRLightsPunctual);
  const bulb = ext.createLight('bulb').setType('point').setIntensity(5).setColor([1, 1, 1]);
  const positions = doc.createAccessor().setType('VEC3').setArray(new Float32Array(floor.positions)).setBuffer(buffer);
  const indices = doc.createAccessor().setType('SCALAR').setArray(new Uint32Array(floor.indices)).setBuffer(buffer);
  const material = doc.createMaterial('floor').setBaseColorFactor([ALBEDO, ALBEDO, ALBEDO, 1]).setMetallicFactor(0).setRoughnessFactor(1);
  const mesh = doc.createMesh('floor').addPrimitive(doc.createPrimitive().setAttribute('POSITION', positions).setIndices(indices).setMaterial(material));
  const scene = doc.createScene('s');
  scene.addChild(doc.createNode('floor').setMesh(mesh));
  scene.addChild(doc.createNode('bulb').setTranslation([0.3, 1.2, -0.4]).setExtension('KHR_lights_punctual', bulb));
  const gltf = await loadGltfScene(doc);
  assert.equal(gltf.lights?.length, 1);
  const device = await testDevice();
  // KHR_materials_ior is absent, so the floor has glTF's default ior 1.5 (a thin specular layer):
  // compare with the same material given by hand.
  const renderer = await createWavefrontPathTracingComputeRenderer({ device, width: SIZE, height: SIZE, samplesPerPixel: 16, seed: 11, maxDepth: 3, ...gltf, camera });
  const byHand = await render([{ type: 'point', position: [0.3, 1.2, -0.4], intensity: 5 }], 16, { meshes: [{ ...floor, material: { baseColorFactor: [ALBEDO, ALBEDO, ALBEDO, 1], metallicFactor: 0, roughnessFactor: 1 } }] });
  try {
    await renderer.renderFrame();
    const image = (await renderer.readRadiance()).data;
    let a = 0;
    let b = 0;
    for (let k = 0; k < SIZE * SIZE; k++) {
      a += image[4 * k + 1]!;
      b += byHand[4 * k + 1]!;
    }
    assert.ok(b > 0 && Math.abs(a - b) < 0.02 * b, `glTF ${a} vs by hand ${b}`);
  } finally {
    renderer.destroy();
  }
});
