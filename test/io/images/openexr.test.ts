import { test } from 'node:test';
import assert from 'node:assert/strict';
import { decodeOpenExr } from '../../../src/io/images/openexr.ts';
import { encodeExr, exrSource } from './environment-encoders.ts';

test('OpenEXR: uncompressed and ZIP, half and float, decode within the format precision, top row first', async () => {
  const w = 24;
  const h = 19;
  const rgb = exrSource(w, h);
  for (const pixel of ['half', 'float'] as const) {
    for (const compression of ['none', 'zip'] as const) {
      const image = await decodeOpenExr(encodeExr(w, h, rgb, pixel, compression));
      assert.equal(image.width, w);
      assert.equal(image.height, h);
      for (let t = 0; t < w * h; t++) {
        for (let c = 0; c < 3; c++) {
          const want = rgb[3 * t + c]!;
          const tol = pixel === 'half' ? 2 ** -11 * Math.abs(want) + 2 ** -24 : 2 ** -24 * Math.abs(want);
          assert.ok(Math.abs(image.data[4 * t + c]! - want) <= tol, `${pixel}/${compression} texel ${t} channel ${c}: ${image.data[4 * t + c]} vs ${want}`);
        }
      }
    }
  }
});
