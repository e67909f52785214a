// texture-sampling.wesl on real WebGPU against the CPU reference (reference-sampler.ts), and the
// atlas's isolation of textures from their neighbours.
//
// Tolerance: the atlas holds rgba8unorm texels, which both sides read exactly (byte / 255), and the
// reference computes texel coordinates in f32 exactly as WGSL does (correctly rounded * and -), so
// both pick the same texels and the same filter weights. What is left is f32 rounding in the
// bilinear and trilinear mixes (a few ulp of values <= 1) and WGSL's pow accuracy in the sRGB
// decode (pow = exp2(y log2 x): log2 and exp2 carry a few ulp, and the 2.4 exponent scales them),
// all far below 1e-5, while a wrong texel, weight or level would move a value by about an 8-bit
// step (0.004) or much more with these random textures.
import assert from 'node:assert/strict';
import { after, test } from 'node:test';
import {
  SAMPLER_MAG_LINEAR,
  SAMPLER_MIN_LINEAR,
  SAMPLER_MIP_LINEAR,
  SAMPLER_MIPMAPS,
  SAMPLER_WRAP_CLAMP,
  SAMPLER_WRAP_MIRROR,
  SAMPLER_WRAP_REPEAT,
  SAMPLER_WRAP_S_SHIFT,
  SAMPLER_WRAP_T_SHIFT,
  TEXTURE_BINDING_FLAG_SRGB,
} from '../../../src/gpu-layout/constants.ts';
import { textureBindingLayout, textureInfoLayout } from '../../../src/gpu-layout/records.ts';
import { Vec4Heap } from '../../../src/gpu-layout/vec4-heap.ts';
import { BufferUsage } from '../../../src/gpu/webgpu-constants.ts';
import { mipChainLayout } from '../../../src/materials/textures/atlas-layout.ts';
import {
  readTextureBinding,
  readTextureInfo,
  sampleTexture,
  sampleTextureInfo,
  textureLod,
  transformUv,
  type AtlasTexels,
  type Rgba,
} from '../../../src/materials/textures/reference-sampler.ts';
import { buildTextureAtlas, type TextureUsage } from '../../../src/materials/textures/texture-atlas.ts';
import { textureTransformMatrix } from '../../../src/scene/texture-transform.ts';
import { uploadTextureAtlas } from '../../../src/materials/textures/upload-texture-atlas.ts';
import type { WavefrontTextureInput, WavefrontTextureTransformInput, WavefrontWrapMode } from '../../../src/scene/types.ts';
import { readBuffer, testDevice, uploadBuffer } from '../../helpers/gpu.ts';
import { rng } from '../../helpers/random.ts';
import { runTestProgram } from '../../helpers/wgsl.ts';
import { constantLevel, handAtlas } from './atlas-fixtures.ts';

const TOLERANCE = 1e-5;
const device = await testDevice();
const destroy: { destroy(): void }[] = [];
after(() => destroy.forEach((d) => d.destroy()));

const sampleKernel = `
import package::materials::textures::texture_sampling::sample_texture;

struct Query { uv: vec2f, lod: f32, info: u32, srgb: u32, p0: u32, p1: u32, p2: u32 }
@group(3) @binding(20) var<storage, read> queries: array<Query>;
@group(3) @binding(21) var<storage, read_write> results: array<vec4f>;

@compute @workgroup_size(64) fn main(@builtin(global_invocation_id) gid: vec3u) {
  let i = gid.x;
  if (i >= arrayLength(&queries)) { return; }
  let q = queries[i];
  results[i] = sample_texture(q.info, q.uv, q.lod, q.srgb != 0u);
}
`;

const boundKernel = `
import package::materials::textures::texture_sampling::{sample_bound_texture, transform_uv, texture_lod, TextureFootprint};
import package::layout::heaps::{load_texture_binding, load_texture_info};

struct BoundQuery { uv0: vec2f, uv1: vec2f, width_over_cos: f32, world_area: f32, uv_area: vec2f, binding: u32, p0: u32, p1: u32, p2: u32 }
@group(3) @binding(20) var<storage, read> queries: array<BoundQuery>;
@group(3) @binding(21) var<storage, read_write> results: array<vec4f>;

@compute @workgroup_size(64) fn main(@builtin(global_invocation_id) gid: vec3u) {
  let i = gid.x;
  if (i >= arrayLength(&queries)) { return; }
  let q = queries[i];
  let footprint = TextureFootprint(q.width_over_cos, q.world_area, q.uv_area);
  let b = load_texture_binding(q.binding);
  let uv = transform_uv(b, select(q.uv0, q.uv1, b.texCoord == 1u));
  results[2u * i] = sample_bound_texture(q.binding, q.uv0, q.uv1, footprint);
  results[2u * i + 1u] = vec4f(uv, texture_lod(b, load_texture_info(b.texture), footprint), 0.0);
}
`;

interface SampleQuery {
  uv: [number, number];
  lod: number;
  info: number;
  srgb: boolean;
}

/** Runs sample_texture for every query on the GPU against an uploaded atlas and heap. */
async function gpuSample(atlas: AtlasTexels, heap: ArrayBuffer, queries: readonly SampleQuery[]): Promise<Float32Array> {
  const bytes = new ArrayBuffer(queries.length * 32);
  const view = new DataView(bytes);
  queries.forEach((q, i) => {
    view.setFloat32(i * 32, q.uv[0], true);
    view.setFloat32(i * 32 + 4, q.uv[1], true);
    view.setFloat32(i * 32 + 8, q.lod, true);
    view.setUint32(i * 32 + 12, q.info, true);
    view.setUint32(i * 32 + 16, q.srgb ? 1 : 0, true);
  });
  const uploaded = uploadTextureAtlas(device, atlas);
  const materials = uploadBuffer(device, heap);
  const queryBuffer = uploadBuffer(device, bytes);
  const results = device.createBuffer({ size: queries.length * 16, usage: BufferUsage.STORAGE | BufferUsage.COPY_SRC });
  destroy.push(uploaded.texture, materials, queryBuffer, results);
  await runTestProgram(device, {
    source: sampleKernel,
    resources: { materials, textureAtlas: uploaded.view, queries: queryBuffer, results },
    workgroups: Math.ceil(queries.length / 64),
  });
  return new Float32Array(await readBuffer(device, results));
}

function maxError(got: Float32Array, at: number, want: Rgba): number {
  return Math.max(...want.map((w, c) => Math.abs(got[at + c]! - w)));
}

function randomImage(width: number, height: number, next: () => number): { width: number; height: number; data: Uint8Array } {
  return { width, height, data: Uint8Array.from({ length: width * height * 4 }, () => Math.floor(next() * 256)) };
}

const wrapModes: WavefrontWrapMode[] = ['repeat', 'clamp-to-edge', 'mirrored-repeat'];

/** Textures of assorted sizes covering every wrap pair, both mag filters and all six min filters. */
function samplerZoo(seed: number): { textures: WavefrontTextureInput[]; usages: TextureUsage[] } {
  const next = rng(seed);
  const sizes: [number, number][] = [[13, 7], [8, 8], [1, 5], [32, 16], [5, 5], [3, 1], [16, 3], [7, 12], [2, 2]];
  const minFilters = ['nearest', 'linear', 'nearest-mipmap-nearest', 'linear-mipmap-nearest', 'nearest-mipmap-linear', 'linear-mipmap-linear'] as const;
  const textures: WavefrontTextureInput[] = [];
  let k = 0;
  for (const wrapS of wrapModes) {
    for (const wrapT of wrapModes) {
      const [w, h] = sizes[k % sizes.length]!;
      textures.push({
        image: randomImage(w, h, next),
        sampler: { wrapS, wrapT, magFilter: k % 2 === 0 ? 'linear' : 'nearest', minFilter: minFilters[k % minFilters.length]! },
      });
      k++;
    }
  }
  // Every min filter with linear magnification on one shared image, and each texture used as sRGB
  // colour and as linear data on alternating textures (some both ways).
  textures.push(...minFilters.map((minFilter) => ({ image: textures[3]!.image, sampler: { magFilter: 'linear' as const, minFilter } })));
  const usages: TextureUsage[] = textures.flatMap((_, t) => (t % 3 === 0 ? [{ texture: t, srgb: true }, { texture: t, srgb: false }] : [{ texture: t, srgb: t % 3 === 1 }]));
  return { textures, usages };
}

test('sample_texture matches the CPU reference: every wrap mode, filter and mip mode, sRGB and linear, uv outside [0, 1]', async () => {
  const { textures, usages } = samplerZoo(1);
  const heap = new Vec4Heap();
  // A small layer limit spreads the blocks over several layers (and downscales the 32x16 texture).
  const atlas = buildTextureAtlas({ textures }, usages, heap, { maxTextureDimension2D: 32, maxTextureArrayLayers: 16 });
  assert.ok(atlas.layers.length >= 2, `several layers (got ${atlas.layers.length})`);
  const heapBytes = heap.finish();
  const next = rng(2);
  const queries: SampleQuery[] = [];
  const randomUv = (): [number, number] => [Math.fround(-2.5 + 6 * next()), Math.fround(-2.5 + 6 * next())];
  for (let i = 0; i < 6000; i++) {
    const u = usages[i % usages.length]!;
    queries.push({ uv: randomUv(), lod: Math.fround(-1 + 7 * next()), info: atlas.infoOffset(u.texture, u.srgb), srgb: u.srgb });
  }
  // Level-of-detail ties: where the magnification switch and the nearest-mip rule decide.
  for (const u of usages) {
    for (const lod of [0, 0.5, 1, 1.5, 2, 2.5, 3.5]) {
      for (let k = 0; k < 8; k++) queries.push({ uv: randomUv(), lod, info: atlas.infoOffset(u.texture, u.srgb), srgb: u.srgb });
    }
  }
  const got = await gpuSample(atlas, heapBytes, queries);
  let worst = 0;
  queries.forEach((q, i) => {
    const want = sampleTexture(atlas, heapBytes, q.info, q.uv, q.lod, q.srgb);
    const err = maxError(got, i * 4, want);
    worst = Math.max(worst, err);
    assert.ok(err <= TOLERANCE, `query ${i} (${JSON.stringify(q)}, sampler ${readTextureInfo(heapBytes, q.info).sampler}): GPU [${[...got.subarray(i * 4, i * 4 + 4)]}] vs CPU [${want}]`);
  });
  console.log(`sample_texture: ${queries.length} queries, largest GPU - CPU difference ${worst.toExponential(2)}`);
});

test('sample_bound_texture matches the CPU reference: KHR_texture_transform, both uv sets, ray-cone LOD', async () => {
  const { textures, usages } = samplerZoo(3);
  const heap = new Vec4Heap();
  const atlas = buildTextureAtlas({ textures }, usages, heap, { maxTextureDimension2D: 128, maxTextureArrayLayers: 16 });
  const transforms: WavefrontTextureTransformInput[] = [
    {},
    { offset: [0.25, -0.5] },
    { scale: [2, 0.5] },
    { rotation: 0.3 },
    { offset: [0, 1], rotation: Math.PI / 2, scale: [0.5, 0.5] },
    { offset: [0.1, 0.2], rotation: -1.1, scale: [3, -1.5] },
  ];
  const bindings: number[] = [];
  usages.forEach((u, k) => {
    const transform = transforms[k % transforms.length]!;
    bindings.push(
      heap.append(textureBindingLayout, {
        ...textureTransformMatrix(transform),
        texture: atlas.infoOffset(u.texture, u.srgb),
        texCoord: k % 2,
        scale: 1,
        flags: u.srgb ? TEXTURE_BINDING_FLAG_SRGB : 0,
      }),
    );
  });
  const heapBytes = heap.finish();
  const next = rng(4);
  const count = 4000;
  const stride = 48;
  const bytes = new ArrayBuffer(count * stride);
  const view = new DataView(bytes);
  const queries = Array.from({ length: count }, (_, i) => {
    const f32 = (x: number): number => Math.fround(x);
    const q = {
      uv0: [f32(-1.5 + 4 * next()), f32(-1.5 + 4 * next())] as [number, number],
      uv1: [f32(-1.5 + 4 * next()), f32(-1.5 + 4 * next())] as [number, number],
      // Cone widths spanning magnification to the smallest levels; some without a footprint.
      footprint: {
        widthOverCos: i % 17 === 0 ? 0 : f32(2 ** (-9 + 7 * next())),
        worldArea: f32(0.01 + next()),
        uvArea: [f32(0.001 + 0.2 * next()), f32(0.001 + 0.2 * next())] as [number, number],
      },
      binding: bindings[i % bindings.length]!,
    };
    const o = i * stride;
    [q.uv0[0], q.uv0[1], q.uv1[0], q.uv1[1], q.footprint.widthOverCos, q.footprint.worldArea, q.footprint.uvArea[0], q.footprint.uvArea[1]].forEach((v, c) =>
      view.setFloat32(o + c * 4, v, true),
    );
    view.setUint32(o + 32, q.binding, true);
    return q;
  });
  const uploaded = uploadTextureAtlas(device, atlas);
  const materials = uploadBuffer(device, heapBytes);
  const queryBuffer = uploadBuffer(device, bytes);
  const results = device.createBuffer({ size: count * 32, usage: BufferUsage.STORAGE | BufferUsage.COPY_SRC });
  destroy.push(uploaded.texture, materials, queryBuffer, results);
  await runTestProgram(device, {
    source: boundKernel,
    resources: { materials, textureAtlas: uploaded.view, queries: queryBuffer, results },
    workgroups: Math.ceil(count / 64),
  });
  const got = new Float32Array(await readBuffer(device, results));
  let worstUv = 0;
  let worstLod = 0;
  let worst = 0;
  let sameInputs = 0;
  queries.forEach((q, i) => {
    const b = readTextureBinding(heapBytes, q.binding);
    const info = readTextureInfo(heapBytes, b.texture);
    const uv = transformUv(b, b.texCoord === 1 ? q.uv1 : q.uv0);
    const lod = textureLod(b, info, q.footprint);
    const [gu, gv, glod] = [got[i * 8 + 4]!, got[i * 8 + 5]!, got[i * 8 + 6]!];
    // transform_uv and texture_lod agree with f64 to f32 precision (uv within 1e-6 absolute for |uv| < 10,
    // lod within WGSL's log2 accuracy).
    worstUv = Math.max(worstUv, Math.abs(gu - uv[0]), Math.abs(gv - uv[1]));
    worstLod = Math.max(worstLod, Math.abs(glod - lod));
    assert.ok(Math.abs(gu - uv[0]) <= 1e-5 && Math.abs(gv - uv[1]) <= 1e-5, `query ${i}: GPU uv (${gu}, ${gv}) vs CPU (${uv})`);
    assert.ok(Math.abs(glod - lod) <= 1e-4, `query ${i}: GPU lod ${glod} vs CPU ${lod}`);
    // The sample: the reference at the GPU's own uv and lod, so a texel boundary or a nearest-mip
    // threshold that f32 rounding puts on the other side cannot flip the comparison.
    const srgb = (b.flags & TEXTURE_BINDING_FLAG_SRGB) !== 0;
    const want = sampleTextureInfo(atlas, info, [gu, gv], glod, srgb);
    const err = maxError(got, i * 8, want);
    worst = Math.max(worst, err);
    assert.ok(err <= TOLERANCE, `query ${i}: GPU [${[...got.subarray(i * 8, i * 8 + 4)]}] vs CPU [${want}]`);
    if (maxError(got, i * 8, sampleTextureInfo(atlas, info, uv, lod, srgb)) <= TOLERANCE) sameInputs++;
  });
  // With the CPU's own uv and lod the reference disagrees only where rounding crossed a boundary.
  assert.ok(sameInputs >= count * 0.99, `${sameInputs} of ${count} agree with the CPU's own uv and lod`);
  console.log(`sample_bound_texture: ${count} queries, uv ${worstUv.toExponential(2)}, lod ${worstLod.toExponential(2)}, sample ${worst.toExponential(2)}; ${sameInputs} agree at the CPU's own uv and lod`);
});

/** uvs on and just around every edge and corner of the texture, in and out of [0, 1]. */
function borderUvs(w: number, h: number): [number, number][] {
  const along = (n: number): number[] => [-1, -0.999, -0.5 / n, -1e-4, 0, 1e-4, 0.25 / n, 0.5 / n, 0.5, 1 - 0.5 / n, 1 - 1e-4, 1, 1 + 1e-4, 1 + 0.5 / n, 2, 2.0001];
  return along(w).flatMap((u) => along(h).map((v) => [Math.fround(u), Math.fround(v)] as [number, number]));
}

const lods = [-1, 0, 0.3, 0.5, 0.9, 1, 1.4, 1.5, 2, 2.7, 3, 3.2, 5, 12];

test('no bleeding: a texture packed among neighbours of another colour never shows them, in any wrap mode, at any level', async () => {
  const green = (w: number, h: number) => ({ width: w, height: h, data: constantLevel(w, h, [0, 255, 0, 255]) });
  const magenta = (w: number, h: number) => ({ width: w, height: h, data: constantLevel(w, h, [255, 0, 255, 255]) });
  const images = [green(6, 10), magenta(6, 10), magenta(9, 10), magenta(4, 4), magenta(12, 5)];
  // The green image once per wrap pair (one shared block), neighbours all around it.
  const textures: WavefrontTextureInput[] = [];
  for (const wrapS of wrapModes) for (const wrapT of wrapModes) textures.push({ image: 0, sampler: { wrapS, wrapT } });
  const neighbours = [1, 2, 3, 4, 1, 2].map((image) => textures.push({ image }) - 1);
  const heap = new Vec4Heap();
  const usages = [...textures.keys()].map((texture) => ({ texture, srgb: texture % 2 === 0 }));
  const atlas = buildTextureAtlas({ images, textures }, usages, heap, { maxTextureDimension2D: 32, maxTextureArrayLayers: 4 });
  const heapBytes = heap.finish();
  // Green has two blocks (sRGB and linear mip chains). The neighbours share their layers; then
  // every texel outside green's own levels (the blocks' unused corners included) is painted
  // magenta, so any read outside them shows.
  const greenInfos = [true, false].map((srgb) => readTextureInfo(heapBytes, atlas.infoOffset(srgb ? 0 : 1, srgb)));
  const neighbourLayers = neighbours.map((t) => readTextureInfo(heapBytes, atlas.infoOffset(t, t % 2 === 0)).layer);
  assert.ok(greenInfos.every((g) => neighbourLayers.includes(g.layer)), 'neighbours share the green blocks\' layers');
  const inside = atlas.layers.map(() => new Uint8Array(atlas.layerSize ** 2));
  for (const g of greenInfos) {
    for (const r of mipChainLayout(g.size[0], g.size[1], g.mipCount).levels) {
      for (let y = 0; y < r.height; y++) for (let x = 0; x < r.width; x++) inside[g.layer]![(g.origin[1] + r.y + y) * atlas.layerSize + g.origin[0] + r.x + x] = 1;
    }
  }
  atlas.layers.forEach((layer, l) => inside[l]!.forEach((isGreen, i) => isGreen || layer.set([255, 0, 255, 255], i * 4)));
  const queries: SampleQuery[] = [];
  for (let t = 0; t < 9; t++) {
    for (const uv of borderUvs(6, 10)) for (const lod of lods) queries.push({ uv, lod, info: atlas.infoOffset(t, t % 2 === 0), srgb: t % 2 === 0 });
  }
  const got = await gpuSample(atlas, heapBytes, queries);
  queries.forEach((q, i) => {
    const rgba = [...got.subarray(i * 4, i * 4 + 4)];
    assert.ok(Math.abs(rgba[0]!) < 1e-6 && Math.abs(rgba[1]! - 1) < 1e-6 && Math.abs(rgba[2]!) < 1e-6, `texture ${Math.floor(i / (queries.length / 9))} at ${q.uv} lod ${q.lod}: [${rgba}]`);
  });
});

test('no bleeding between the levels of one texture: per-level colours blend exactly as the mip rule says', async () => {
  // Hand-made levels of constant, distinct colours (B = 60 k / 255, G = 1), poison (R = 1) everywhere else.
  const [w, h] = [8, 6];
  const levelBlue = [0, 60, 120, 180];
  const levels = levelBlue.map((b, k) => constantLevel(Math.max(1, w >> k), Math.max(1, h >> k), [0, 255, b, 255]));
  const queries: SampleQuery[] = [];
  const expected: number[] = [];
  const heap = new Vec4Heap();
  let fixture: ReturnType<typeof handAtlas> | undefined;
  for (const s of [SAMPLER_WRAP_REPEAT, SAMPLER_WRAP_CLAMP, SAMPLER_WRAP_MIRROR]) {
    for (const t of [SAMPLER_WRAP_REPEAT, SAMPLER_WRAP_CLAMP, SAMPLER_WRAP_MIRROR]) {
      const sampler = (s << SAMPLER_WRAP_S_SHIFT) | (t << SAMPLER_WRAP_T_SHIFT) | SAMPLER_MAG_LINEAR | SAMPLER_MIN_LINEAR | SAMPLER_MIPMAPS | SAMPLER_MIP_LINEAR;
      fixture = handAtlas(w, h, levels, sampler);
      const info = heap.append(textureInfoLayout, { ...fixture.info, origin: [...fixture.info.origin], size: [...fixture.info.size] });
      for (const uv of borderUvs(w, h)) {
        for (const lod of lods) {
          queries.push({ uv, lod, info, srgb: false });
          // Trilinear between floor(lod) and the next level, lod clamped to [0, levels - 1].
          const level = Math.min(Math.max(lod, 0), levels.length - 1);
          const l0 = Math.floor(level);
          const l1 = Math.min(l0 + 1, levels.length - 1);
          expected.push(((1 - (level - l0)) * levelBlue[l0]! + (level - l0) * levelBlue[l1]!) / 255);
        }
      }
    }
  }
  const got = await gpuSample(fixture!.atlas, heap.finish(), queries);
  queries.forEach((q, i) => {
    const rgba = [...got.subarray(i * 4, i * 4 + 4)];
    assert.ok(Math.abs(rgba[0]!) < 1e-6 && Math.abs(rgba[1]! - 1) < 1e-6 && Math.abs(rgba[2]! - expected[i]!) < 1e-6, `${q.uv} lod ${q.lod}: [${rgba}], blue should be ${expected[i]}`);
  });
});

test('an empty atlas uploads as a 1x1x1 texture', () => {
  const uploaded = uploadTextureAtlas(device, { layerSize: 1, layers: [] });
  destroy.push(uploaded.texture);
  assert.deepEqual([uploaded.texture.width, uploaded.texture.height, uploaded.texture.depthOrArrayLayers, uploaded.bytes], [1, 1, 1, 4]);
});
