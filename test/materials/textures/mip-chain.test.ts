import assert from 'node:assert/strict';
import { test } from 'node:test';
import { fullMipCount, mipLevelSize } from '../../../src/materials/textures/atlas-layout.ts';
import { downscaleImage, generateMipChain, type Rgba8Image, type TexelEncoding } from '../../../src/materials/textures/mip-chain.ts';
import { rng } from '../../helpers/random.ts';

// The reference: the exact sRGB curve (IEC 61966-2-1:1999) written out here, not imported.
const decode = (c: number): number => (c <= 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055) ** 2.4);
const encode = (l: number): number => (l <= 0.0031308 ? l * 12.92 : 1.055 * l ** (1 / 2.4) - 0.055);

function randomImage(width: number, height: number, seed: number): Rgba8Image {
  const next = rng(seed);
  const data = new Uint8Array(width * height * 4);
  for (let i = 0; i < data.length; i++) data[i] = Math.floor(next() * 256);
  return { width, height, data };
}

/** Length of [a0, a1) intersected with [b0, b1). */
const overlap = (a0: number, a1: number, b0: number, b1: number): number => Math.max(0, Math.min(a1, b1) - Math.max(a0, b0));

/**
 * The exact value a texel of a w x h level should hold, as a real number of 8-bit steps: the 2-D
 * area integral of level 0 over the texel's footprint (brute force over every level-0 texel it
 * touches), in linear light for sRGB colour.
 */
function footprintMean(image: Rgba8Image, dw: number, dh: number, x: number, y: number, c: number, encoding: TexelEncoding): number {
  const sx = image.width / dw;
  const sy = image.height / dh;
  const [x0, x1, y0, y1] = [x * sx, (x + 1) * sx, y * sy, (y + 1) * sy];
  const srgb = encoding === 'srgb' && c < 3;
  let sum = 0;
  let area = 0;
  for (let j = Math.floor(y0); j < Math.ceil(y1); j++) {
    for (let i = Math.floor(x0); i < Math.ceil(x1); i++) {
      const a = overlap(x0, x1, i, i + 1) * overlap(y0, y1, j, j + 1);
      const byte = image.data[(j * image.width + i) * 4 + c]!;
      sum += a * (srgb ? decode(byte / 255) : byte / 255);
      area += a;
    }
  }
  const mean = sum / area;
  return 255 * (srgb ? encode(mean) : mean);
}

function checkLevel(image: Rgba8Image, texels: Uint8Array, dw: number, dh: number, encoding: TexelEncoding, label: string): void {
  assert.equal(texels.length, dw * dh * 4, `${label}: size`);
  for (let y = 0; y < dh; y++) {
    for (let x = 0; x < dw; x++) {
      for (let c = 0; c < 4; c++) {
        const exact = footprintMean(image, dw, dh, x, y, c, encoding);
        const stored = texels[(y * dw + x) * 4 + c]!;
        // Correctly rounded to 8 bits (either neighbour only at an exact tie, up to f64 rounding).
        assert.ok(Math.abs(stored - exact) <= 0.5 + 1e-9, `${label} texel ${x},${y} channel ${c}: stored ${stored}, exact ${exact}`);
      }
    }
  }
}

const sizes: [number, number][] = [[1, 1], [2, 2], [3, 3], [5, 7], [7, 5], [1, 9], [9, 1], [8, 8], [16, 4], [13, 11], [6, 10], [17, 16]];

for (const encoding of ['srgb', 'linear'] as const) {
  test(`every ${encoding} mip level is the area-weighted mean of level 0 over its footprint (odd and pow2 sizes)`, () => {
    sizes.forEach(([w, h], i) => {
      const image = randomImage(w, h, 101 + i);
      const chain = generateMipChain(image, encoding);
      assert.equal(chain.length, fullMipCount(w, h));
      assert.deepEqual([...chain[0]!], [...image.data], 'level 0 is the image');
      for (let k = 1; k < chain.length; k++) {
        const [dw, dh] = mipLevelSize(w, h, k);
        checkLevel(image, chain[k]!, dw, dh, encoding, `${w}x${h} ${encoding} level ${k}`);
      }
    });
  });
}

test('sRGB averaging happens in linear light: black and white average to sRGB 188, not 128', () => {
  const image: Rgba8Image = { width: 2, height: 1, data: new Uint8Array([0, 0, 0, 0, 255, 255, 255, 255]) };
  const [, srgbLevel] = generateMipChain(image, 'srgb');
  const [, linearLevel] = generateMipChain(image, 'linear');
  // encode(0.5) = 0.7354 -> 187.5 ... rounds to 188; alpha stays linear: 127.5 -> 128.
  assert.deepEqual([...srgbLevel!], [188, 188, 188, 128]);
  assert.deepEqual([...linearLevel!], [128, 128, 128, 128]);
});

test('a constant image stays exactly constant in every level', () => {
  for (const encoding of ['srgb', 'linear'] as const) {
    const image: Rgba8Image = { width: 11, height: 6, data: new Uint8Array(11 * 6 * 4).map((_, i) => [13, 200, 77, 255][i % 4]!) };
    for (const level of generateMipChain(image, encoding).slice(1)) {
      for (let i = 0; i < level.length; i++) assert.equal(level[i], [13, 200, 77, 255][i % 4]);
    }
  }
});

test('downscaling to an arbitrary smaller size is the same footprint mean', () => {
  const image = randomImage(23, 17, 7);
  for (const [dw, dh] of [[11, 8], [5, 17], [23, 3], [1, 1]] as const) {
    for (const encoding of ['srgb', 'linear'] as const) {
      const small = downscaleImage(image, dw, dh, encoding);
      checkLevel(image, small.data, dw, dh, encoding, `23x17 -> ${dw}x${dh} ${encoding}`);
    }
  }
  assert.throws(() => downscaleImage(image, 24, 17, 'linear'), RangeError);
});
