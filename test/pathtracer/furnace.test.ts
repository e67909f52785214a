// White furnace tests (the renderer end to end): in a uniform environment of radiance L, a convex
// Lambertian object of albedo a reflects exactly a * L (every reflected ray escapes), and pixels that
// miss it see L. Any bias in NEE, MIS weights, BSDF sampling or Russian roulette shows up here.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import { createWavefrontPathTracingComputeConfig } from '../../src/pathtracer/config.ts';
import { createWavefrontReferenceRay } from '../../src/pathtracer/reference.ts';
import { testDevice } from '../helpers/gpu.ts';
import { icosphere } from '../helpers/meshes.ts';
import { gltfBsdfEval, type GltfBsdfMaterial } from '../../src/materials/gltf-bsdf-reference.ts';

const size = 48;
const camera = { position: [0, 0, 4], target: [0, 0, 0], up: [0, 1, 0], fovYDegrees: 40 };
const L = [0.8, 1.0, 1.3];

/** Pixels whose four corners all hit a sphere of radius rIn (inside) or all miss one of radius rOut (outside). */
function classifyPixels(rIn: number, rOut = rIn): { inside: number[]; outside: number[] } {
  const config = createWavefrontPathTracingComputeConfig({ width: size, height: size, camera });
  const hits = (x: number, y: number, r: number): boolean => {
    const ray = createWavefrontReferenceRay(config, { pixel: [x, y], jitter: [0, 0] });
    const o = ray.origin, d = ray.direction;
    const b = o[0] * d[0] + o[1] * d[1] + o[2] * d[2];
    const c = o[0] ** 2 + o[1] ** 2 + o[2] ** 2 - r * r;
    return b * b - c >= 0;
  };
  const inside: number[] = [];
  const outside: number[] = [];
  for (let y = 0; y < size; y++) {
    for (let x = 0; x < size; x++) {
      const corner = (r: number): boolean[] => [hits(x, y, r), hits(x + 1, y, r), hits(x, y + 1, r), hits(x + 1, y + 1, r)];
      if (corner(rIn).every(Boolean)) inside.push(y * size + x);
      else if (!corner(rOut).some(Boolean)) outside.push(y * size + x);
    }
  }
  return { inside, outside };
}

function meanOver(data: Float32Array, pixels: number[]): number[] {
  const m = [0, 0, 0];
  for (const p of pixels) for (let c = 0; c < 3; c++) m[c]! += data[4 * p + c]!;
  return m.map((v) => v / pixels.length);
}

async function furnace(
  scene: { meshes?: unknown[]; sceneObjects?: unknown[]; energyCompensation?: boolean; integrator?: 'megakernel' },
  radii: [number, number],
  expected: (c: number, inside: number[]) => number,
  tolerance: number,
): Promise<void> {
  const device = await testDevice();
  const renderer = await createWavefrontPathTracingComputeRenderer({
    device, width: size, height: size, maxDepth: 8, samplesPerPixel: 32, seed: 7, camera, environment: { color: L },
    ...(scene as object),
  });
  try {
    const stats = await renderer.renderFrame();
    assert.equal(stats.invalidSamples, 0);
    const { data } = await renderer.readRadiance();
    const { inside, outside } = classifyPixels(radii[0], radii[1]);
    assert.ok(inside.length > 300 && outside.length > 300);
    const mIn = meanOver(data, inside);
    const mOut = meanOver(data, outside);
    for (let c = 0; c < 3; c++) {
      assert.ok(Math.abs(mOut[c]! - L[c]!) < 1e-5 * L[c]!, `background channel ${c}: ${mOut[c]} vs ${L[c]}`);
      const e = expected(c, inside);
      assert.ok(Math.abs(mIn[c]! - e) < tolerance * e, `object channel ${c}: ${mIn[c]} vs ${e}`);
    }
  } finally {
    renderer.destroy();
  }
}

test('white furnace: Lambertian analytic sphere of albedo a in environment L renders a*L, background L', async () => {
  const a = [0.9, 0.5, 0.2];
  await furnace(
    { sceneObjects: [{ type: 'sphere', center: [0, 0, 0], radius: 1, color: a, metallic: 0, roughness: 1, ior: 1 }] },
    [1, 1],
    (c) => a[c]! * L[c]!,
    0.01,
  );
});

test('white furnace: albedo-1 Lambertian triangle mesh (flat icosphere) renders exactly L', async () => {
  const sphere = icosphere(1, [0, 0, 0], 3);
  // A radius below the tessellation's inscribed sphere bounds "inside" pixels, the vertex radius "outside" ones.
  await furnace(
    { meshes: [{ positions: sphere.positions, indices: sphere.indices, material: { baseColorFactor: [1, 1, 1, 1], metallicFactor: 0, roughnessFactor: 1, ior: 1 } }] },
    [0.97, 1],
    (c) => L[c]!,
    0.01,
  );
});

test('white furnace, megakernel integrator: albedo-1 Lambertian icosphere renders exactly L', async () => {
  const sphere = icosphere(1, [0, 0, 0], 3);
  await furnace(
    { integrator: 'megakernel', meshes: [{ positions: sphere.positions, indices: sphere.indices, material: { baseColorFactor: [1, 1, 1, 1], metallicFactor: 0, roughnessFactor: 1, ior: 1 } }] },
    [0.97, 1],
    (c) => L[c]!,
    0.01,
  );
});

/** Directional albedo E(mu) = integral of f cos over the hemisphere, from the independent JS BSDF (midpoint quadrature). */
function directionalAlbedo(m: GltfBsdfMaterial, mu: number): number {
  const wo: [number, number, number] = [Math.sqrt(Math.max(0, 1 - mu * mu)), 0, mu];
  const nt = 256, np = 256;
  let sum = 0;
  for (let i = 0; i < nt; i++) {
    // Quadrature in cos(theta) so the cosine factor and solid angle are exact.
    const ct = (i + 0.5) / nt;
    const st = Math.sqrt(1 - ct * ct);
    for (let j = 0; j < np; j++) {
      const phi = ((j + 0.5) / np) * 2 * Math.PI;
      sum += gltfBsdfEval(m, wo, [st * Math.cos(phi), st * Math.sin(phi), ct])[0] * ct;
    }
  }
  return (sum * 2 * Math.PI) / (nt * np);
}

test('furnace: a rough conductor with F0 = 1 renders its single-scattering albedo (independent JS quadrature)', async () => {
  const material: GltfBsdfMaterial = { baseColor: [1, 1, 1], metallic: 1, roughness: 0.6, ior: 1.5 };
  const table = Array.from({ length: 33 }, (_, k) => directionalAlbedo(material, Math.max(1e-3, k / 32)));
  const albedoAt = (mu: number): number => {
    const x = Math.min(32, Math.max(0, mu * 32));
    const k = Math.min(31, Math.floor(x));
    return table[k]! + (table[k + 1]! - table[k]!) * (x - k);
  };
  const config = createWavefrontPathTracingComputeConfig({ width: size, height: size, camera });
  // Expected pixel value: E(mu) * L averaged over each pixel (4x4 sub-pixel rays), then over the disk.
  const expectedMean = (inside: number[]): number => {
    let total = 0;
    for (const p of inside) {
      let acc = 0;
      for (let s = 0; s < 16; s++) {
        const ray = createWavefrontReferenceRay(config, { pixel: [p % size, Math.floor(p / size)], jitter: [((s % 4) + 0.5) / 4, (Math.floor(s / 4) + 0.5) / 4] });
        const o = ray.origin, d = ray.direction;
        const b = o[0] * d[0] + o[1] * d[1] + o[2] * d[2];
        const t = -b - Math.sqrt(b * b - (o[0] ** 2 + o[1] ** 2 + o[2] ** 2 - 1));
        const n = [o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]];
        acc += albedoAt(-(n[0]! * d[0] + n[1]! * d[1] + n[2]! * d[2]));
      }
      total += acc / 16;
    }
    return total / inside.length;
  };
  assert.ok(table.every((e) => e <= 1 + 1e-6), 'a conductor with F0 = 1 never reflects more than it receives');
  // The single-scattering model alone: multiple-scattering compensation (on by default) off.
  await furnace(
    { sceneObjects: [{ type: 'sphere', center: [0, 0, 0], radius: 1, color: [1, 1, 1], metallic: 1, roughness: 0.6 }], energyCompensation: false },
    [1, 1],
    (c, inside) => expectedMean(inside) * L[c]!,
    0.015,
  );
});
