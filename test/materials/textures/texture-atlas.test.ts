import assert from 'node:assert/strict';
import { test } from 'node:test';
import { GpuRendererError } from '../../../src/errors/gpu-renderer-error.ts';
import {
  SAMPLER_MAG_LINEAR,
  SAMPLER_MIN_LINEAR,
  SAMPLER_MIP_LINEAR,
  SAMPLER_MIPMAPS,
  SAMPLER_WRAP_CLAMP,
  SAMPLER_WRAP_MIRROR,
  SAMPLER_WRAP_S_SHIFT,
  SAMPLER_WRAP_T_SHIFT,
} from '../../../src/gpu-layout/constants.ts';
import { Vec4Heap } from '../../../src/gpu-layout/vec4-heap.ts';
import { fullMipCount, mipChainLayout } from '../../../src/materials/textures/atlas-layout.ts';
import { generateMipChain } from '../../../src/materials/textures/mip-chain.ts';
import { readTextureInfo, sampleTextureInfo, type TextureInfoRecord } from '../../../src/materials/textures/reference-sampler.ts';
import { buildTextureAtlas, type TextureAtlas, type TextureUsage } from '../../../src/materials/textures/texture-atlas.ts';
import type { WavefrontImageInput, WavefrontTextureInput } from '../../../src/scene/types.ts';
import { rng } from '../../helpers/random.ts';

const bigLimits = { maxTextureDimension2D: 8192, maxTextureArrayLayers: 256 };

function randomImage(width: number, height: number, seed: number): WavefrontImageInput {
  const next = rng(seed);
  return { width, height, data: Uint8Array.from({ length: width * height * 4 }, () => Math.floor(next() * 256)) };
}

function expectInvalid(fn: () => unknown, field: string): void {
  assert.throws(fn, (e: unknown) => {
    assert.ok(e instanceof GpuRendererError, `expected a GpuRendererError, got ${String(e)}`);
    assert.equal(e.code, 'INVALID_TEXTURE');
    assert.equal(e.field, field);
    return true;
  });
}

/** The texels of `info`'s level `k` read straight from the atlas layers. */
function readLevel(atlas: TextureAtlas, info: TextureInfoRecord, k: number): Uint8Array {
  const rect = mipChainLayout(info.size[0], info.size[1], info.mipCount).levels[k]!;
  const out = new Uint8Array(rect.width * rect.height * 4);
  const layer = atlas.layers[info.layer]!;
  for (let y = 0; y < rect.height; y++) {
    const from = ((info.origin[1] + rect.y + y) * atlas.layerSize + info.origin[0] + rect.x) * 4;
    out.set(layer.subarray(from, from + rect.width * 4), y * rect.width * 4);
  }
  return out;
}

test('every used texture lands in the atlas with its whole mip chain, in the encoding it is used with', () => {
  const images = [randomImage(13, 7, 1), randomImage(8, 8, 2), randomImage(1, 5, 3)];
  const textures: WavefrontTextureInput[] = [
    { image: 0 },
    { image: 1, sampler: { minFilter: 'linear' } },
    { image: 2, sampler: { minFilter: 'nearest-mipmap-nearest' } },
    { image: randomImage(6, 3, 4) },
  ];
  const usages: TextureUsage[] = [
    { texture: 0, srgb: true },
    { texture: 0, srgb: false },
    { texture: 1, srgb: true },
    { texture: 2, srgb: false },
    { texture: 3, srgb: true },
  ];
  const heap = new Vec4Heap();
  const atlas = buildTextureAtlas({ textures, images }, usages, heap, bigLimits);
  const bytes = heap.finish();
  assert.equal(atlas.textureCount, 4);
  assert.equal(atlas.layers.length * atlas.layerSize ** 2 * 4, atlas.bytes);
  for (const u of usages) {
    const info = readTextureInfo(bytes, atlas.infoOffset(u.texture, u.srgb));
    const t = textures[u.texture]!;
    const image = typeof t.image === 'number' ? images[t.image]! : t.image;
    assert.deepEqual(info.size, [image.width, image.height]);
    const mipmapped = !['nearest', 'linear'].includes(t.sampler?.minFilter ?? 'linear-mipmap-linear');
    assert.equal(info.mipCount, mipmapped ? fullMipCount(image.width, image.height) : 1, `texture ${u.texture} mip count`);
    const chain = generateMipChain({ width: image.width, height: image.height, data: image.data as Uint8Array }, u.srgb ? 'srgb' : 'linear', info.mipCount);
    for (let k = 0; k < info.mipCount; k++) assert.deepEqual(readLevel(atlas, info, k), chain[k], `texture ${u.texture} ${u.srgb ? 'sRGB' : 'linear'} level ${k}`);
  }
  // Texture 0 is mipmapped and used both ways: two blocks. Texture 1 needs level 0 only: one.
  assert.notDeepEqual(readTextureInfo(bytes, atlas.infoOffset(0, true)).origin, readTextureInfo(bytes, atlas.infoOffset(0, false)).origin);
  assert.equal(atlas.blockCount, 5);
});

test('textures sharing an image share its block, each with its own sampler bits', () => {
  const images = [randomImage(16, 16, 5)];
  const textures: WavefrontTextureInput[] = [
    { image: 0, sampler: { wrapS: 'clamp-to-edge', wrapT: 'mirrored-repeat', magFilter: 'nearest', minFilter: 'nearest-mipmap-linear' } },
    { image: 0 },
    { image: 0, sampler: { minFilter: 'nearest' } },
  ];
  const heap = new Vec4Heap();
  const atlas = buildTextureAtlas({ textures, images }, [0, 1, 2].map((texture) => ({ texture, srgb: true })), heap, bigLimits);
  const bytes = heap.finish();
  assert.equal(atlas.blockCount, 1);
  const infos = [0, 1, 2].map((t) => readTextureInfo(bytes, atlas.infoOffset(t, true)));
  for (const info of infos) assert.deepEqual([info.origin, info.layer, info.mipCount], [infos[0]!.origin, infos[0]!.layer, 5]);
  assert.equal(infos[0]!.sampler, (SAMPLER_WRAP_CLAMP << SAMPLER_WRAP_S_SHIFT) | (SAMPLER_WRAP_MIRROR << SAMPLER_WRAP_T_SHIFT) | SAMPLER_MIPMAPS | SAMPLER_MIP_LINEAR);
  assert.equal(infos[1]!.sampler, SAMPLER_MAG_LINEAR | SAMPLER_MIN_LINEAR | SAMPLER_MIPMAPS | SAMPLER_MIP_LINEAR);
  assert.equal(infos[2]!.sampler, SAMPLER_MAG_LINEAR);
});

test('unused textures take no atlas space; an empty atlas has no layers', () => {
  const heap = new Vec4Heap();
  const atlas = buildTextureAtlas({ textures: [{ image: randomImage(4, 4, 6) }] }, [], heap, bigLimits);
  assert.deepEqual([atlas.layers.length, atlas.bytes, atlas.textureCount, heap.size], [0, 0, 0, 0]);
  assert.throws(() => atlas.infoOffset(0, true), GpuRendererError);
});

test('level 0 of every texture samples back exactly at texel centres (nearest, lod 0)', () => {
  const images = [randomImage(9, 4, 7), randomImage(3, 11, 8), randomImage(16, 2, 9)];
  const textures: WavefrontTextureInput[] = images.map((_, i) => ({ image: i, sampler: { magFilter: 'nearest' } }));
  const heap = new Vec4Heap();
  const atlas = buildTextureAtlas({ textures, images }, textures.map((_, t) => ({ texture: t, srgb: false })), heap, bigLimits);
  const bytes = heap.finish();
  images.forEach((image, t) => {
    const info = readTextureInfo(bytes, atlas.infoOffset(t, false));
    for (let y = 0; y < image.height; y++) {
      for (let x = 0; x < image.width; x++) {
        const got = sampleTextureInfo(atlas, info, [(x + 0.5) / image.width, (y + 0.5) / image.height], 0, false);
        const at = (y * image.width + x) * 4;
        assert.deepEqual(got.map((v) => Math.round(v * 255)), [...image.data.subarray(at, at + 4)], `texture ${t} texel ${x},${y}`);
      }
    }
  });
});

test('a texture too large for the device is downscaled by halving, with a warning naming it', () => {
  const images = [randomImage(100, 90, 10)];
  const textures: WavefrontTextureInput[] = [{ image: randomImage(4, 4, 11) }, { image: 0 }, { image: 0, sampler: { minFilter: 'linear' } }];
  const warnings: string[] = ['earlier warning'];
  const heap = new Vec4Heap();
  const atlas = buildTextureAtlas({ textures, images }, [{ texture: 0, srgb: true }, { texture: 1, srgb: true }, { texture: 2, srgb: false }], heap, { maxTextureDimension2D: 64, maxTextureArrayLayers: 8 }, warnings);
  const bytes = heap.finish();
  // With its mip chain, 100x90 needs a 150-wide block: 25x22 (block 37x22) is the first halving that fits 64.
  const mipped = readTextureInfo(bytes, atlas.infoOffset(1, true));
  assert.deepEqual(mipped.size, [25, 22]);
  // Level 0 alone: 50x45 fits.
  assert.deepEqual(readTextureInfo(bytes, atlas.infoOffset(2, false)).size, [50, 45]);
  assert.deepEqual(atlas.warnings, [
    'textures[1]: 100x90 downscaled to 25x22 to fit maxTextureDimension2D 64 with its mip chain',
    'textures[2]: 100x90 downscaled to 50x45 to fit maxTextureDimension2D 64',
  ]);
  assert.deepEqual(warnings, ['earlier warning', ...atlas.warnings]);
  assert.ok(atlas.layerSize <= 64);
});

test('more layers than the device allows is SCENE_TOO_LARGE naming textures', () => {
  const textures: WavefrontTextureInput[] = Array.from({ length: 5 }, (_, i) => ({ image: randomImage(40, 40, 20 + i), sampler: { minFilter: 'linear' } }));
  assert.throws(
    () => buildTextureAtlas({ textures }, textures.map((_, t) => ({ texture: t, srgb: true })), new Vec4Heap(), { maxTextureDimension2D: 64, maxTextureArrayLayers: 4 }),
    (e: unknown) => e instanceof GpuRendererError && e.code === 'SCENE_TOO_LARGE' && e.field === 'textures',
  );
});

test('bad textures and images are INVALID_TEXTURE errors naming the field', () => {
  const good = randomImage(2, 2, 30);
  const build = (textures: unknown, images?: unknown, usages: TextureUsage[] = []) =>
    buildTextureAtlas({ textures: textures as WavefrontTextureInput[], images: images as WavefrontImageInput[] }, usages, new Vec4Heap(), bigLimits);
  expectInvalid(() => build([{ image: 0 }], [good, { width: 2, height: 2, data: new Uint8Array(15) }]), 'images[1].data');
  expectInvalid(() => build([], [{ width: 0, height: 2, data: new Uint8Array(0) }]), 'images[0].width');
  expectInvalid(() => build([], [{ width: 2, height: 1.5, data: new Uint8Array(12) }]), 'images[0].height');
  expectInvalid(() => build([], [{ width: 1, height: 1, data: [0, 0, 256, 0] }]), 'images[0].data[2]');
  expectInvalid(() => build([], [{ width: 1, height: 1, data: 'abcd' }]), 'images[0].data');
  expectInvalid(() => build([{ image: 0 }, { image: 3 }], [good]), 'textures[1].image');
  expectInvalid(() => build([{ image: { width: 2, height: 2 } }]), 'textures[0].image.data');
  expectInvalid(() => build([{ image: 0 }, { image: 0 }, { image: 0, sampler: { wrapS: 'clamp' } }], [good]), 'textures[2].sampler.wrapS');
  expectInvalid(() => build([{ image: 0, sampler: { wrapT: 3 } }], [good]), 'textures[0].sampler.wrapT');
  expectInvalid(() => build([{ image: 0, sampler: { magFilter: 'linear-mipmap-linear' } }], [good]), 'textures[0].sampler.magFilter');
  expectInvalid(() => build([{ image: 0, sampler: { minFilter: 'bilinear' } }], [good]), 'textures[0].sampler.minFilter');
  expectInvalid(() => build([null], [good]), 'textures[0]');
  expectInvalid(() => build([{ image: 0 }], [good], [{ texture: 1, srgb: true }]), 'textures');
  // Plain arrays of bytes are accepted (scene JSON).
  const atlas = build([{ image: 0 }], [{ width: 1, height: 1, data: [1, 2, 3, 4] }], [{ texture: 0, srgb: false }]);
  assert.deepEqual([...atlas.layers[0]!.subarray(0, 4)], [1, 2, 3, 4]);
});
