// The shared scene representation end to end: textures sampled on the GPU at the hit's uv (uv sets,
// KHR_texture_transform, wrap modes, sRGB decoding, vertex colours), alpha MASK and BLEND, instances
// equal to their flattened geometry (mirroring transforms included), shader specialisation that does
// not change the image, first-hit AOVs, and the vertex streams (normals, tangents, normal maps).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import { srgbToLinear } from '../../src/film/tone-mapping.ts';
import { createCornellBoxScene } from '../../src/scene/cornell-box.ts';
import type { WavefrontFrameStats, WavefrontMaterialInput, WavefrontMeshInput, WavefrontPathTracingOptions, WavefrontTextureInput } from '../../src/index.ts';
import { LUMINANCE_FRACTION_BITS } from '../../src/gpu-layout/constants.ts';
import { testDevice } from '../helpers/gpu.ts';

const SIZE = 16;
/** Orthographic camera whose 16 x 16 pixels tile the square [-1, 1]^2 of the z = 0 plane. */
const camera = { type: 'orthographic' as const, position: [0, 0, 2], target: [0, 0, 0], up: [0, 1, 0], orthographicHeight: 2 };

/** The square [-1, 1]^2 facing +z, uv (0, 0) at the top left (glTF), uv1 mirrored in u. */
function square(material: WavefrontMaterialInput | number, extra: Partial<WavefrontMeshInput> = {}): WavefrontMeshInput {
  return {
    positions: [-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0],
    indices: [0, 1, 2, 0, 2, 3],
    normals: [0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1],
    uvs: [0, 1, 1, 1, 1, 0, 0, 0],
    uvs1: [1, 1, 0, 1, 0, 0, 1, 0],
    material,
    ...extra,
  };
}

async function renderWithStats(options: Partial<WavefrontPathTracingOptions>, spp = 16): Promise<{ radiance: Float32Array; stats: WavefrontFrameStats }> {
  const device = await testDevice();
  const renderer = await createWavefrontPathTracingComputeRenderer({ device, width: SIZE, height: SIZE, samplesPerPixel: spp, seed: 3, maxDepth: 4, camera, environment: { color: [1, 1, 1] }, ...options });
  try {
    const stats = await renderer.renderFrame();
    assert.equal(stats.invalidSamples, 0);
    return { radiance: (await renderer.readRadiance()).data, stats };
  } finally {
    renderer.destroy();
  }
}

async function render(options: Partial<WavefrontPathTracingOptions>, spp = 16): Promise<Float32Array> {
  return (await renderWithStats(options, spp)).radiance;
}

/** A 4 x 4 RGBA8 texture of distinct colours, nearest filtering. */
const texels = Uint8Array.from({ length: 64 }, (_, i) => (i % 4 === 3 ? 255 : (37 * i + 11) % 256));
const nearest = (wrap: 'repeat' | 'clamp-to-edge' | 'mirrored-repeat'): WavefrontTextureInput => ({
  image: { width: 4, height: 4, data: texels },
  sampler: { magFilter: 'nearest', minFilter: 'nearest', wrapS: wrap, wrapT: wrap },
});
const lambert = { metallicFactor: 0, roughnessFactor: 1, ior: 1 };
/** The linear albedo of texel (i, j) times a factor: a Lambertian plane in a uniform environment of radiance 1 shows exactly that. */
const texelAlbedo = (i: number, j: number, c: number): number => srgbToLinear(texels[4 * (4 * j + i) + c]! / 255);

/**
 * Every 4 x 4 block of pixels (one texel of the 4 x 4 textures) averages to the expected radiance
 * within `tolerance` (relative): NEE and BSDF sampling of a uniform environment have variance, so
 * pixels are compared in blocks of 16 pixels x spp samples.
 */
function assertBlocksShow(data: Float32Array, expected: (x: number, y: number, c: number) => number, tolerance: number, what: string): void {
  for (let by = 0; by < SIZE; by += 4) {
    for (let bx = 0; bx < SIZE; bx += 4) {
      for (let c = 0; c < 3; c++) {
        let got = 0;
        let want = 0;
        for (let y = by; y < by + 4; y++) {
          for (let x = bx; x < bx + 4; x++) {
            got += data[4 * (y * SIZE + x) + c]! / 16;
            want += expected(x, y, c) / 16;
          }
        }
        assert.ok(Math.abs(got - want) <= tolerance * Math.max(want, 0.05), `${what}: block (${bx}, ${by}) channel ${c}: ${got} vs ${want}`);
      }
    }
  }
}

function assertPlaneShows(data: Float32Array, expected: (x: number, y: number, c: number) => number, tolerance: number, what: string): void {
  for (let y = 0; y < SIZE; y++) {
    for (let x = 0; x < SIZE; x++) {
      for (let c = 0; c < 3; c++) {
        const got = data[4 * (y * SIZE + x) + c]!;
        const want = expected(x, y, c);
        assert.ok(Math.abs(got - want) <= tolerance * Math.max(want, 0.05), `${what}: pixel (${x}, ${y}) channel ${c}: ${got} vs ${want}`);
      }
    }
  }
}

test('a base-colour texture is sampled at the hit uv (sRGB decoded, times factor and vertex colour)', async () => {
  const data = await render({
    textures: [nearest('repeat')],
    meshes: [square({ ...lambert, baseColorFactor: [1, 0.8, 1, 1], baseColorTexture: { index: 0 } }, { colors: Array.from({ length: 4 }, () => [1, 1, 0.5, 1]).flat() })],
  }, 64);
  // Pixel x covers u in [x/16, (x+1)/16): texel floor(x / 4); likewise v and y.
  assertBlocksShow(data, (x, y, c) => texelAlbedo(x >> 2, y >> 2, c) * [1, 0.8, 0.5][c]!, 0.02, 'uv0');
});

test('uv set 1 with KHR_texture_transform and repeat wrapping', async () => {
  const data = await render({
    textures: [nearest('repeat')],
    meshes: [square({ ...lambert, baseColorTexture: { index: 0, texCoord: 1, transform: { offset: [0.5, 0] } } })],
  }, 64);
  // uv1 = (1 - u, v), shifted by half a texture in u and wrapped.
  const column = (x: number): number => Math.floor(4 * ((1 - (x + 0.5) / SIZE + 0.5) % 1));
  assertBlocksShow(data, (x, y, c) => texelAlbedo(column(x), y >> 2, c), 0.02, 'uv1 + transform');
});

test('alpha MASK cuts holes that camera rays pass through; BLEND is stochastic opacity', async () => {
  // Alpha 0 in the left half of the texture, 255 in the right; a black plane.
  const alpha = Uint8Array.from({ length: 64 }, (_, i) => (i % 4 === 3 ? ((i >> 2) % 4 < 2 ? 0 : 255) : 255));
  const mask = await render({
    textures: [{ image: { width: 4, height: 4, data: alpha }, sampler: { magFilter: 'nearest', minFilter: 'nearest' } }],
    meshes: [square({ ...lambert, baseColorFactor: [0, 0, 0, 1], alphaMode: 'MASK', alphaCutoff: 0.5, baseColorTexture: { index: 0 } })],
  });
  // Through a hole the environment shows at exactly its radiance; the black plane reflects nothing.
  assertPlaneShows(mask, (x) => (x < SIZE / 2 ? 1 : 0), 1e-6, 'MASK');
  const blend = await render({ meshes: [square({ ...lambert, baseColorFactor: [0, 0, 0, 0.25], alphaMode: 'BLEND' })] }, 64);
  let mean = 0;
  for (let i = 0; i < SIZE * SIZE; i++) mean += blend[4 * i]! / (SIZE * SIZE);
  // A camera ray passes with probability 1 - alpha = 0.75; binomial standard error ~0.0034.
  assert.ok(Math.abs(mean - 0.75) < 0.014, `BLEND mean ${mean}`);
});

/** Rotation about y by `deg`, then scale, then translation, as a column-major 4x4. */
function transform(t: number[], deg: number, s: number[]): number[] {
  const c = Math.cos((deg * Math.PI) / 180), n = Math.sin((deg * Math.PI) / 180);
  return [c * s[0]!, 0, -n * s[0]!, 0, 0, s[1]!, 0, 0, n * s[2]!, 0, c * s[2]!, 0, t[0]!, t[1]!, t[2]!, 1];
}

function applyTransform(m: number[], mesh: { positions: number[]; indices: number[] }): { positions: number[]; indices: number[] } {
  const positions: number[] = [];
  for (let i = 0; i < mesh.positions.length; i += 3) {
    const [x, y, z] = mesh.positions.slice(i, i + 3) as [number, number, number];
    for (let r = 0; r < 3; r++) positions.push(m[r]! * x + m[4 + r]! * y + m[8 + r]! * z + m[12 + r]!);
  }
  // A mirroring transform reverses the winding; flip it back so the front face is kept.
  const det = m[0]! * (m[5]! * m[10]! - m[9]! * m[6]!) - m[4]! * (m[1]! * m[10]! - m[9]! * m[2]!) + m[8]! * (m[1]! * m[6]! - m[5]! * m[2]!);
  const indices = det < 0 ? mesh.indices.flatMap((_, k) => (k % 3 === 0 ? [mesh.indices[k]!, mesh.indices[k + 2]!, mesh.indices[k + 1]!] : [])) : mesh.indices;
  return { positions, indices };
}

test('instances render as their flattened world-space geometry, mirroring transforms included', async () => {
  const cube = {
    positions: [-1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1, -1, -1, 1, 1, -1, 1, 1, 1, 1, -1, 1, 1],
    indices: [0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4, 3, 7, 6, 3, 6, 2, 0, 4, 7, 0, 7, 3, 1, 2, 6, 1, 6, 5],
  };
  const light = { positions: [-1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, 1], indices: [0, 1, 2, 0, 2, 3] };
  const floor = { positions: [-3, -1, 3, 3, -1, 3, 3, -1, -3, -3, -1, -3], indices: [0, 1, 2, 0, 2, 3] };
  const diffuse: WavefrontMaterialInput = { ...lambert, baseColorFactor: [0.7, 0.6, 0.5] };
  const emitter: WavefrontMaterialInput = { ...lambert, baseColorFactor: [0, 0, 0], emissiveFactor: [1, 0.9, 0.7], emissiveStrength: 6 };
  const placements = [
    { mesh: 0, transform: transform([-0.8, -0.5, 0], 30, [0.4, 0.5, 0.4]) },
    { mesh: 0, transform: transform([0.8, -0.6, 0.2], -20, [-0.35, 0.4, 0.3]) },
    // Emitters face down: the light quad's counter-clockwise side is +y, so mirror it in y.
    { mesh: 1, transform: transform([-0.4, 1.5, 0], 10, [0.5, -1, 0.5]) },
    { mesh: 1, transform: transform([0.6, 1.4, 0.3], -35, [-0.4, 1, 0.4]) },
    { mesh: 2 },
  ];
  const base = { width: 40, height: 40, samplesPerPixel: 8, seed: 9, maxDepth: 5, camera: { position: [0, 0.5, 5], target: [0, 0, 0], fovYDegrees: 50 }, environment: { color: [0.05, 0.05, 0.08] } };
  const device = await testDevice();
  const run = async (options: Partial<WavefrontPathTracingOptions>): Promise<Float32Array> => {
    const renderer = await createWavefrontPathTracingComputeRenderer({ device, ...base, ...options });
    try {
      const stats = await renderer.renderFrame();
      assert.equal(stats.invalidSamples, 0);
      assert.equal(renderer.getSnapshot().lightCount, 4, 'the two emitter instances each contribute their two triangles');
      return (await renderer.readRadiance()).data;
    } finally {
      renderer.destroy();
    }
  };
  const instanced = await run({
    materials: [diffuse, emitter],
    meshes: [{ ...cube, material: 0 }, { ...light, material: 1 }, { ...floor, material: 0 }],
    instances: placements,
  });
  const identity = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];
  const flattened = await run({
    meshes: placements.map((p) => ({ ...applyTransform(p.transform ?? identity, [cube, light, floor][p.mesh]!), material: p.mesh === 1 ? emitter : diffuse })),
  });
  // Same world geometry, same samples: the images agree up to f32 rounding of the transforms, which
  // can move a rare grazing path.
  let close = 0;
  let sumA = 0, sumB = 0;
  for (let i = 0; i < instanced.length; i += 4) {
    const d = Math.max(...[0, 1, 2].map((c) => Math.abs(instanced[i + c]! - flattened[i + c]!) / Math.max(0.01, flattened[i + c]!)));
    if (d < 1e-3) close++;
    sumA += instanced[i]!;
    sumB += flattened[i]!;
  }
  assert.ok(close >= 0.97 * (instanced.length / 4), `${close} of ${instanced.length / 4} pixels agree`);
  assert.ok(Math.abs(sumA - sumB) <= 0.01 * sumB, `mean radiance ${sumA} vs ${sumB}`);
  assert.ok(sumB / (instanced.length / 4) > 0.05, 'the emitters light the scene');
});

test('specialisation compiles unused features out without changing the image', async () => {
  const scene = createCornellBoxScene();
  const a = await renderWithStats({ ...scene, camera: scene.camera, environment: { color: [0, 0, 0] } }, 4);
  const b = await renderWithStats({ ...scene, camera: scene.camera, environment: { color: [0, 0, 0] }, shaderSpecialization: 'off' }, 4);
  const specialised = a.radiance;
  const general = b.radiance;
  let sum = 0;
  for (let i = 0; i < specialised.length; i++) {
    assert.ok(Math.abs(specialised[i]! - general[i]!) <= 1e-6 * Math.max(1, general[i]!), `value ${i}: ${specialised[i]} vs ${general[i]}`);
    sum += specialised[i]!;
  }
  assert.ok(sum > 0);
  // The frame diagnostics too: a CPU adapter's kernels tally them per invocation, the general
  // kernels (every feature in) per workgroup. Each fixed-point add rounds by at most half a unit
  // (2^-16), so the means per pixel sample differ by at most that.
  const bound = 0.5 * 2 ** -LUMINANCE_FRACTION_BITS;
  for (const key of ['totalLuminance', 'emitterLuminance', 'environmentLuminance'] as const) {
    assert.ok(Math.abs(a.stats.terminalRadiance[key] - b.stats.terminalRadiance[key]) <= bound, `${key}: ${a.stats.terminalRadiance[key]} vs ${b.stats.terminalRadiance[key]}`);
  }
  assert.ok(a.stats.terminalRadiance.emitterLuminance > 0, 'some samples see the light');
  assert.equal(a.stats.terminalRadiance.samples, b.stats.terminalRadiance.samples);
});

test('first-hit AOVs: albedo, shading normal and depth of the first non-specular hit', async () => {
  const device = await testDevice();
  const renderer = await createWavefrontPathTracingComputeRenderer({
    device, width: SIZE, height: SIZE, samplesPerPixel: 4, camera, environment: { color: [1, 1, 1] }, aovs: true,
    meshes: [square({ ...lambert, baseColorFactor: [0.2, 0.4, 0.6] })],
  });
  try {
    await renderer.renderFrame();
    const albedo = (await renderer.readAov('albedo')).data;
    const normal = (await renderer.readAov('normal')).data;
    const depth = (await renderer.readAov('depth')).data;
    for (let i = 0; i < SIZE * SIZE; i++) {
      [0.2, 0.4, 0.6].forEach((a, c) => assert.ok(Math.abs(albedo[4 * i + c]! - a) < 1e-6, `albedo ${albedo[4 * i + c]}`));
      [0, 0, 1].forEach((n, c) => assert.ok(Math.abs(normal[4 * i + c]! - n) < 1e-4, `normal ${normal[4 * i + c]}`));
      assert.ok(Math.abs(depth[4 * i]! - 2) < 1e-5, `depth ${depth[4 * i]}`);
    }
  } finally {
    renderer.destroy();
  }
  const plain = await createWavefrontPathTracingComputeRenderer({ device, width: 8, height: 8, meshes: [square(lambert)] });
  await assert.rejects(plain.readAov('albedo'), (e: unknown) => (e as { code?: string }).code === 'INVALID_STATE');
  plain.destroy();
});

/** Mean normal AOV of the image (every pixel sees the square). */
async function meanNormal(meshes: WavefrontMeshInput[], textures: WavefrontTextureInput[] = []): Promise<Float32Array> {
  const device = await testDevice();
  const renderer = await createWavefrontPathTracingComputeRenderer({ device, width: SIZE, height: SIZE, samplesPerPixel: 2, camera, environment: { color: [1, 1, 1] }, aovs: true, meshes, textures });
  try {
    await renderer.renderFrame();
    return (await renderer.readAov('normal')).data;
  } finally {
    renderer.destroy();
  }
}

test('vertex streams: interpolated normals, degenerate normals, and normal maps with authored or derived tangents', async () => {
  // Normals tilted towards +x on the right edge: the AOV at each pixel is the interpolated normal,
  // renormalised (the image is flat in y, so rows agree; compare at pixel centres within the
  // variation across one pixel).
  const tilt = 0.5;
  const n = [0, 0, 1, tilt, 0, 1, tilt, 0, 1, 0, 0, 1];
  const tilted = await meanNormal([square(lambert, { normals: n })]);
  for (let x = 0; x < SIZE; x++) {
    const s = (x + 0.5) / SIZE;
    const want = [tilt * s, 0, 1];
    const len = Math.hypot(...want);
    for (let c = 0; c < 3; c++) {
      const got = tilted[4 * (5 * SIZE + x) + c]!;
      assert.ok(Math.abs(got - want[c]! / len) < 0.02, `pixel ${x} channel ${c}: ${got} vs ${want[c]! / len}`);
    }
  }
  // A zero normal at vertex 2, which both triangles share: they shade with the geometric normal
  // (vertex 1's tilt does not show either).
  const degenerate = await meanNormal([square(lambert, { normals: [0, 0, 1, tilt, 0, 1, 0, 0, 0, 0, 0, 1] })]);
  for (let i = 0; i < SIZE * SIZE; i++) [0, 0, 1].forEach((w, c) => assert.ok(Math.abs(degenerate[4 * i + c]! - w) < 1e-4, `degenerate: ${degenerate[4 * i + c]}`));

  // A constant linear normal map m = (0, 0.6, 0.8): n = normalize(T m.x + B m.y + N m.z) with
  // B = cross(N, T) * tangent.w (glTF 2.0 section 3.7.2.1).
  const texel = [128, 204, 230, 255];
  const m = texel.slice(0, 3).map((t) => (t / 255) * 2 - 1);
  const mapped = (sign: number): number[] => {
    const v = [m[0]!, sign * m[1]!, m[2]!];
    const len = Math.hypot(...v);
    return v.map((c) => c / len);
  };
  const normalMap: WavefrontTextureInput = { image: { width: 1, height: 1, data: Uint8Array.from(texel) } };
  const material = { ...lambert, normalTexture: { index: 0 } };
  const tangents = (w: number): number[] => Array.from({ length: 4 }, () => [1, 0, 0, w]).flat();
  const plus = await meanNormal([square(material, { tangents: tangents(1) })], [normalMap]);
  const minus = await meanNormal([square(material, { tangents: tangents(-1) })], [normalMap]);
  // No tangents: T = dp/du = +x and the bitangent towards decreasing v, +y (v grows downwards and a
  // normal map's +Y is up), as tangent w = +1.
  const derived = await meanNormal([square(material)], [normalMap]);
  for (let i = 0; i < SIZE * SIZE; i++) {
    for (let c = 0; c < 3; c++) {
      assert.ok(Math.abs(plus[4 * i + c]! - mapped(1)[c]!) < 1e-3, `w = +1 channel ${c}: ${plus[4 * i + c]} vs ${mapped(1)[c]}`);
      assert.ok(Math.abs(minus[4 * i + c]! - mapped(-1)[c]!) < 1e-3, `w = -1 channel ${c}: ${minus[4 * i + c]} vs ${mapped(-1)[c]}`);
      assert.ok(Math.abs(derived[4 * i + c]! - mapped(1)[c]!) < 1e-3, `derived channel ${c}: ${derived[4 * i + c]} vs ${mapped(1)[c]}`);
    }
  }
  // Other uv layouts, derived: a quarter turn (u grows along +y, v along +x: T = +y, B = -x) and a
  // mirror in v (v grows upwards: T = +x, B = -y).
  const unit = (v: number[]): number[] => v.map((c) => c / Math.hypot(...v));
  for (const { name, uvs, want } of [
    { name: 'quarter turn', uvs: [0, 0, 0, 1, 1, 1, 1, 0], want: unit([-m[1]!, m[0]!, m[2]!]) },
    { name: 'mirrored v', uvs: [0, 0, 1, 0, 1, 1, 0, 1], want: unit([m[0]!, -m[1]!, m[2]!]) },
  ]) {
    const got = await meanNormal([square(material, { uvs })], [normalMap]);
    for (let i = 0; i < SIZE * SIZE; i++) {
      for (let c = 0; c < 3; c++) assert.ok(Math.abs(got[4 * i + c]! - want[c]!) < 1e-3, `derived, ${name}, channel ${c}: ${got[4 * i + c]} vs ${want[c]}`);
    }
  }
});
