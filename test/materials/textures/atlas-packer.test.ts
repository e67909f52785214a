import assert from 'node:assert/strict';
import { test } from 'node:test';
import { GpuRendererError } from '../../../src/errors/gpu-renderer-error.ts';
import { mipBlockSize, fullMipCount } from '../../../src/materials/textures/atlas-layout.ts';
import { fitTextureToLimit, packAtlas, shelfPack, type AtlasPacking, type BlockSize } from '../../../src/materials/textures/atlas-packer.ts';
import { rng } from '../../helpers/random.ts';

function randomBlocks(count: number, maxSide: number, seed: number): BlockSize[] {
  const next = rng(seed);
  return Array.from({ length: count }, () => ({ width: 1 + Math.floor(next() * maxSide), height: 1 + Math.floor(next() * maxSide) }));
}

/** Brute force: paint every block's texels into its layer and fail on any texel painted twice or outside. */
function assertValidPacking(blocks: readonly BlockSize[], p: AtlasPacking, label: string): void {
  assert.equal(p.placements.length, blocks.length);
  const owners = Array.from({ length: p.layerCount }, () => new Int32Array(p.layerSize * p.layerSize).fill(-1));
  blocks.forEach((b, i) => {
    const { layer, x, y } = p.placements[i]!;
    assert.ok(Number.isInteger(layer) && layer >= 0 && layer < p.layerCount, `${label}: block ${i} layer ${layer}`);
    assert.ok(x >= 0 && y >= 0 && x + b.width <= p.layerSize && y + b.height <= p.layerSize, `${label}: block ${i} inside its layer`);
    const owner = owners[layer]!;
    for (let j = y; j < y + b.height; j++) {
      for (let k = x; k < x + b.width; k++) {
        assert.equal(owner[j * p.layerSize + k], -1, `${label}: blocks ${owner[j * p.layerSize + k]} and ${i} overlap at ${k},${j}`);
        owner[j * p.layerSize + k] = i;
      }
    }
  });
  // No layer is empty.
  owners.forEach((o, l) => assert.ok(o.some((v) => v >= 0), `${label}: layer ${l} is empty`));
}

test('shelf packing: no overlaps, every block inside a layer, for random block sets', () => {
  for (let seed = 1; seed <= 6; seed++) {
    const blocks = randomBlocks(40 + seed * 10, 24, seed);
    const packed = shelfPack(blocks, 64);
    assertValidPacking(blocks, { layerSize: 64, ...packed }, `seed ${seed}`);
  }
});

test('packAtlas picks the power-of-two side >= the largest block that takes the least memory, within the limits, without overlaps', () => {
  const limits = { maxTextureDimension2D: 256, maxTextureArrayLayers: 64 };
  for (let seed = 10; seed < 16; seed++) {
    const blocks = randomBlocks(60, 40, seed);
    const p = packAtlas(blocks, limits);
    const largest = Math.max(...blocks.map((b) => Math.max(b.width, b.height)));
    assert.ok(p.layerSize >= largest && (p.layerSize & (p.layerSize - 1)) === 0 && p.layerSize <= 256, `layer side ${p.layerSize}`);
    assert.ok(p.layerCount <= 64);
    assertValidPacking(blocks, p, `seed ${seed}`);
    // The least memory over every allowed layer side, and reasonably dense.
    const texels = p.layerSize ** 2 * p.layerCount;
    for (let side = 64; side <= 256; side *= 2) {
      if (side < largest) continue;
      assert.ok(texels <= side ** 2 * shelfPack(blocks, side).layerCount, `seed ${seed}: side ${side} would take less memory`);
    }
    const area = blocks.reduce((s, b) => s + b.width * b.height, 0);
    assert.ok(area / texels > 0.5, `seed ${seed}: ${area} block texels in ${texels} atlas texels`);
  }
});

test('packAtlas prefers the smallest single layer: a few small blocks do not get a huge layer', () => {
  const blocks = [{ width: 12, height: 8 }, { width: 6, height: 4 }, { width: 3, height: 2 }];
  const p = packAtlas(blocks, { maxTextureDimension2D: 8192, maxTextureArrayLayers: 256 });
  assert.equal(p.layerSize, 16);
  assert.equal(p.layerCount, 1);
  assertValidPacking(blocks, p, 'small');
});

test('packAtlas spreads over several layers at the size limit when one layer cannot hold everything', () => {
  const blocks = Array.from({ length: 10 }, () => ({ width: 48, height: 32 }));
  const p = packAtlas(blocks, { maxTextureDimension2D: 64, maxTextureArrayLayers: 16 });
  assert.equal(p.layerSize, 64);
  // One 48x32 block per shelf, two shelves per 64x64 layer.
  assert.equal(p.layerCount, 5);
  assertValidPacking(blocks, p, 'multi-layer');
});

test('packAtlas is deterministic', () => {
  const blocks = randomBlocks(80, 30, 99);
  const a = packAtlas(blocks, { maxTextureDimension2D: 128, maxTextureArrayLayers: 64 });
  const b = packAtlas(blocks.map((x) => ({ ...x })), { maxTextureDimension2D: 128, maxTextureArrayLayers: 64 });
  assert.deepEqual(a, b);
});

test('too many layers is SCENE_TOO_LARGE naming textures', () => {
  const blocks = Array.from({ length: 9 }, () => ({ width: 64, height: 64 }));
  assert.throws(
    () => packAtlas(blocks, { maxTextureDimension2D: 64, maxTextureArrayLayers: 8 }),
    (e: unknown) => e instanceof GpuRendererError && e.code === 'SCENE_TOO_LARGE' && e.field === 'textures' && /9 atlas layers/.test(e.message),
  );
  assert.equal(packAtlas(blocks, { maxTextureDimension2D: 64, maxTextureArrayLayers: 9 }).layerCount, 9);
});

test('fitTextureToLimit halves until the block (with its mip chain) fits', () => {
  assert.deepEqual(fitTextureToLimit(9000, 9000, true, 8192), { width: 4500, height: 4500, halvings: 1 });
  assert.deepEqual(fitTextureToLimit(9000, 9000, false, 8192), { width: 4500, height: 4500, halvings: 1 });
  assert.deepEqual(fitTextureToLimit(6000, 100, false, 8192), { width: 6000, height: 100, halvings: 0 });
  // 6000 wide with mips needs 9000 columns: one halving.
  assert.deepEqual(fitTextureToLimit(6000, 100, true, 8192), { width: 3000, height: 50, halvings: 1 });
  for (const [w, h, limit] of [[100, 37, 16], [1, 1000, 64], [513, 2, 256]] as const) {
    const fit = fitTextureToLimit(w, h, true, limit);
    const [bw, bh] = mipBlockSize(fit.width, fit.height, fullMipCount(fit.width, fit.height));
    assert.ok(bw <= limit && bh <= limit);
    // One halving fewer would not fit.
    if (fit.halvings > 0) {
      const [pw, ph] = [Math.max(1, w >> (fit.halvings - 1)), Math.max(1, h >> (fit.halvings - 1))];
      const [qw, qh] = mipBlockSize(pw, ph, fullMipCount(pw, ph));
      assert.ok(qw > limit || qh > limit);
    }
  }
});
