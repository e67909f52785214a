// Raster shading against analytic values: a base-colour texture shows its texels (sRGB decode,
// Lambertian under a unit uniform environment), a directional light gives a floor the radiance
// a E cos / pi, and the shadow map darkens exactly the floor under an occluder; the punctual
// specular, clearcoat and sheen lobes equal the CPU references of the BRDF terms they share with
// the path tracer (src/materials/reference), with the Sample Viewer's f90 Schlick and Neubelt sheen
// visibility written out here.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { schlickWeight } from '../../src/materials/reference/fresnel.ts';
import { ggxDAniso, ggxG2 } from '../../src/materials/reference/microfacet.ts';
import { charlieD, sheenAlpha } from '../../src/materials/extensions/sheen/reference.ts';
import { linearToSrgb, srgbToLinear } from '../../src/film/tone-mapping.ts';
import type { WavefrontMaterialInput } from '../../src/scene/types.ts';
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

test('a directional light on a floor: GGX metal, clearcoat and sheen highlights equal the CPU BRDF terms', async () => {
  // Orthographic top view of a floor; the centre pixel (odd size) lies on the camera's axis, so
  // v = n = +y there. The light travels along (-dx, -1, 0).
  const size = 9;
  const render = async (material: WavefrontMaterialInput, dx: number, E: number): Promise<number> => {
    const renderer = await createRasterRenderer({
      device: await testDevice(),
      width: size,
      height: size,
      toneMapping: 'linear',
      shadow: false,
      camera: { type: 'orthographic', position: [0, 5, 0], target: [0, 0, 0], up: [0, 0, -1], orthographicHeight: 1 },
      lights: [{ type: 'directional', direction: [-dx, -1, 0], intensity: E }],
      meshes: [{ positions: [-2, 0, 2, 2, 0, 2, 2, 0, -2, -2, 0, -2], normals: Array(4).fill([0, 1, 0]).flat(), indices: [0, 1, 2, 0, 2, 3], material }],
    });
    await renderer.render();
    const pixels = await renderer.readPixels();
    renderer.destroy();
    return pixels.data[4 * (((size - 1) / 2) * size + (size - 1) / 2)]!;
  };
  // The shading frame's directions (z = the floor's normal) for a light at dx.
  const geometry = (dx: number) => {
    const len = Math.hypot(dx, 1);
    const l = [dx / len, 0, 1 / len] as const;
    const hl = Math.hypot(l[0], l[2] + 1);
    return { v: [0, 0, 1] as const, l, h: [l[0] / hl, 0, (l[2] + 1) / hl] as const };
  };
  // f cos E of a GGX lobe with Schlick's f90 = 1: F(v.h) D(h) G2 / (4 n.l n.v) n.l E.
  const ggx = (f0: number, roughness: number, dx: number, E: number): number => {
    const { v, l, h } = geometry(dx);
    const a = { x: roughness * roughness, y: roughness * roughness };
    const f = (f0 + (1 - f0) * schlickWeight(h[2])) * ggxDAniso(h, a) * ggxG2(v, l, a) / (4 * l[2]);
    return f * l[2] * E;
  };
  const code = (radiance: number): number => Math.round(linearToSrgb(radiance) * 255);
  const cases = [
    // A metal: f0 = base colour; no diffuse.
    { name: 'metal', material: { baseColorFactor: [0.5, 0.5, 0.5, 1], metallicFactor: 1, roughnessFactor: 0.5 }, dx: 0.4, E: 2, expected: ggx(0.5, 0.5, 0.4, 2) },
    // A clearcoat over a black base that reflects nothing (ior 1): the coat's F0 = 0.04 lobe alone.
    { name: 'clearcoat', material: { baseColorFactor: [0, 0, 0, 1], metallicFactor: 0, roughnessFactor: 1, ior: 1, clearcoatFactor: 1, clearcoatRoughnessFactor: 0.3 }, dx: 0.2, E: 4, expected: ggx(0.04, 0.3, 0.2, 4) },
    // Sheen over the same black base: Charlie D with the Sample Viewer's Neubelt visibility
    // 1 / (4 (n.l + n.v - n.l n.v)), here n.v = 1.
    {
      name: 'sheen',
      material: { baseColorFactor: [0, 0, 0, 1], metallicFactor: 0, roughnessFactor: 1, ior: 1, sheenColorFactor: [1, 1, 1], sheenRoughnessFactor: 0.7 },
      dx: 1,
      E: 16,
      expected: (() => {
        const { l, h } = geometry(1);
        return (charlieD(h[2], sheenAlpha(0.7)) / 4) * l[2] * 16;
      })(),
    },
  ];
  for (const c of cases) {
    assert.ok(c.expected > 0.1 && c.expected < 0.9, `${c.name}: the expected radiance ${c.expected} is well inside the 8-bit range`);
    const got = await render(c.material as WavefrontMaterialInput, c.dx, c.E);
    assert.ok(Math.abs(got - code(c.expected)) <= 1, `${c.name}: ${got} vs ${code(c.expected)} (radiance ${c.expected.toFixed(4)})`);
  }
});
