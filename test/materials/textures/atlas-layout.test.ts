import assert from 'node:assert/strict';
import { test } from 'node:test';
import { fullMipCount, mipBlockSize, mipChainLayout, mipLevelOrigin, mipLevelSize } from '../../../src/materials/textures/atlas-layout.ts';

const sizes: [number, number][] = [
  [1, 1], [1, 2], [2, 1], [1, 16], [16, 1], [1, 7], [7, 1], [3, 3], [5, 3], [3, 5], [7, 9], [13, 6],
  [8, 8], [16, 4], [4, 16], [32, 32], [31, 33], [100, 37], [64, 1], [255, 257], [1024, 2],
];

test('mip count is floor(log2(max side)) + 1 and the last level is 1x1', () => {
  for (const [w, h] of sizes) {
    const n = fullMipCount(w, h);
    assert.equal(n, Math.floor(Math.log2(Math.max(w, h))) + 1, `${w}x${h}`);
    assert.deepEqual(mipLevelSize(w, h, n - 1), [1, 1], `${w}x${h} last level`);
    if (n > 1) assert.notDeepEqual(mipLevelSize(w, h, n - 2), [1, 1], `${w}x${h} level before the last`);
  }
});

test('level sizes follow WebGPU: max(1, floor(size / 2^k))', () => {
  for (const [w, h] of sizes) {
    for (let k = 0; k < fullMipCount(w, h); k++) {
      assert.deepEqual(mipLevelSize(w, h, k), [Math.max(1, Math.floor(w / 2 ** k)), Math.max(1, Math.floor(h / 2 ** k))]);
    }
  }
});

test('mip levels tile their block without overlap, every level inside the block, for many sizes', () => {
  for (const [w, h] of sizes) {
    for (const levels of [1, 2, fullMipCount(w, h)]) {
      if (levels > fullMipCount(w, h)) continue;
      const layout = mipChainLayout(w, h, levels);
      const [bw, bh] = mipBlockSize(w, h, levels);
      assert.equal(layout.blockWidth, bw);
      assert.equal(layout.blockHeight, bh);
      const owner = new Int32Array(bw * bh).fill(-1);
      layout.levels.forEach((r, k) => {
        assert.deepEqual([r.x, r.y], mipLevelOrigin(w, h, k));
        assert.ok(r.x >= 0 && r.y >= 0 && r.x + r.width <= bw && r.y + r.height <= bh, `${w}x${h} level ${k} inside the ${bw}x${bh} block`);
        for (let y = r.y; y < r.y + r.height; y++) {
          for (let x = r.x; x < r.x + r.width; x++) {
            assert.equal(owner[y * bw + x], -1, `${w}x${h}: texel ${x},${y} of level ${k} already holds level ${owner[y * bw + x]}`);
            owner[y * bw + x] = k;
          }
        }
      });
      // The block is tight: level 0 spans its height or the column does, level 0 plus the column its width.
      const column = layout.levels.slice(1);
      const rightEdge = Math.max(...layout.levels.map((r) => r.x + r.width));
      const bottomEdge = Math.max(...layout.levels.map((r) => r.y + r.height));
      assert.equal(rightEdge, bw, `${w}x${h} x${levels}: block width is tight`);
      assert.equal(bottomEdge, bh, `${w}x${h} x${levels}: block height is tight`);
      if (levels > 1) assert.equal(bw, w + Math.max(1, w >> 1));
      assert.equal(bh, Math.max(h, column.reduce((s, r) => s + r.height, 0)));
    }
  }
});
