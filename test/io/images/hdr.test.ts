import { test } from 'node:test';
import assert from 'node:assert/strict';
import { decodeHdr, decodeRadianceHdr } from '../../../src/io/images/radiance-hdr.ts';
import { encodeHdr, encodeRgbe } from '../../../src/io/images/hdr-encode.ts';
import { GpuRendererError } from '../../../src/errors/gpu-renderer-error.ts';
import { rng } from '../../helpers/random.ts';
import { readHdrWithThree } from './independent-readers.ts';
import { assertDecodedMatches, encodeHdr as encodeReferenceHdr, sourceImage } from './environment-encoders.ts';

function radiance(width: number, height: number, seed: number): Float32Array {
  const rand = rng(seed);
  const data = new Float32Array(width * height * 4);
  for (let p = 0; p < width * height; p++) {
    // Runs of identical pixels (so RLE runs occur) mixed with noise over 1e-3 .. 1e4, and zeros.
    const x = p % width;
    const flat = x >= width / 2 && x < (3 * width) / 4;
    for (let c = 0; c < 3; c++) data[4 * p + c] = flat ? 0.75 + c : rand() < 0.05 ? 0 : Math.pow(10, -3 + 7 * rand());
    data[4 * p + 3] = 1;
  }
  return data;
}

const ascii = (bytes: Uint8Array, n: number): string => String.fromCharCode(...bytes.subarray(0, n));

test('header: #?RADIANCE, FORMAT=32-bit_rle_rgbe, a blank line, then -Y H +X W', () => {
  const bytes = encodeHdr({ width: 9, height: 4, data: radiance(9, 4, 1) });
  const text = ascii(bytes, 200);
  assert.ok(text.startsWith('#?RADIANCE\n'));
  const headerEnd = text.indexOf('\n\n');
  assert.ok(headerEnd > 0);
  assert.ok(text.slice(0, headerEnd).split('\n').includes('FORMAT=32-bit_rle_rgbe'));
  assert.ok(text.slice(headerEnd + 2).startsWith('-Y 4 +X 9\n'));
});

test('RGBE pixels: shared exponent from the largest component, mantissas truncated (Ward float2rgbe)', () => {
  const px = new Uint8Array(4);
  encodeRgbe(1, 0.5, 0.25, px, 0); // 1 = 0.5 * 2^1 -> scale 2^7
  assert.deepEqual([...px], [128, 64, 32, 129]);
  encodeRgbe(3, 0, 0.001, px, 0); // 3 = 0.75 * 2^2 -> scale 2^6
  assert.deepEqual([...px], [192, 0, 0, 130]);
  encodeRgbe(0, 0, 0, px, 0);
  assert.deepEqual([...px], [0, 0, 0, 0]);
  encodeRgbe(-5, Number.NaN, 2, px, 0); // RGBE holds no negatives or NaN: they store as 0
  assert.deepEqual([...px], [0, 0, 128, 130]);
  encodeRgbe(Infinity, 1, 0, px, 0); // saturates at the largest exponent
  assert.deepEqual([...px], [255, 0, 0, 255]);
  encodeRgbe(1e-40, 0, 0, px, 0); // below 2^-128: black
  assert.deepEqual([...px], [0, 0, 0, 0]);
  // Exactly a power of two and just below it (log2 rounding must not pick the wrong exponent).
  encodeRgbe(2 ** 20, 0, 0, px, 0);
  assert.deepEqual([...px], [128, 0, 0, 128 + 21]);
  encodeRgbe(2 ** 20 * (1 - 2 ** -40), 0, 0, px, 0);
  assert.deepEqual([...px], [255, 0, 0, 128 + 20]);
});

test('three.js HDRLoader decodes our files within RGBE precision (RLE and flat widths)', () => {
  for (const [width, height] of [
    [64, 5],
    [8, 3],
    [7, 4],
    [1, 1],
  ]) {
    const data = radiance(width, height, width + height);
    const decoded = readHdrWithThree(encodeHdr({ width, height, data }));
    assert.deepEqual([decoded.width, decoded.height], [width, height]);
    for (let p = 0; p < width * height; p++) {
      const max = Math.max(data[4 * p], data[4 * p + 1], data[4 * p + 2]);
      for (let c = 0; c < 3; c++) {
        const v = data[4 * p + c];
        const got = decoded.data[4 * p + c];
        // Truncation loses < 1 step = 2^(e-8) <= max / 128; three decodes b * 2^e / 255, i.e. with a
        // 256/255 scale relative to Ward's b * 2^(e-8), which adds up to v / 255.
        assert.ok(Math.abs(got - v) <= max / 128 + v / 255 + 1e-6 * v, `${width}x${height} pixel ${p} channel ${c}: ${v} -> ${got}`);
      }
    }
  }
});

test('own round trip: decodeHdr(encodeHdr(x)) is within half an RGBE step (Radiance colr_color reconstruction)', () => {
  const width = 40;
  const height = 6;
  const data = radiance(width, height, 4);
  const decoded = decodeHdr(encodeHdr({ width, height, data }));
  for (let p = 0; p < width * height; p++) {
    const max = Math.max(data[4 * p], data[4 * p + 1], data[4 * p + 2]);
    for (let c = 0; c < 3; c++) {
      const v = data[4 * p + c];
      assert.ok(Math.abs(decoded.data[4 * p + c] - v) <= max / 256 + 1e-6 * v, `pixel ${p} channel ${c}`);
    }
    assert.equal(decoded.data[4 * p + 3], 1);
  }
});

test('new-style RLE compresses runs: a constant 256-wide image is far smaller than flat RGBE and decodes identically', () => {
  const width = 256;
  const height = 8;
  const data = new Float32Array(width * height * 4).fill(0.5);
  const bytes = encodeHdr({ width, height, data });
  const headerBytes = ascii(bytes, 200).indexOf(`+X ${width}\n`) + `+X ${width}\n`.length;
  // Per scanline: 4-byte marker + per component two 127-runs (2 bytes each) + a 2-byte literal (3) = 32.
  assert.ok(bytes.length - headerBytes < height * 40, `pixel data ${bytes.length - headerBytes} bytes`);
  const flat = width * height * 4;
  assert.ok(bytes.length - headerBytes < flat / 20);
  const decoded = readHdrWithThree(bytes);
  const own = decodeHdr(bytes);
  for (let i = 0; i < width * height; i++) {
    assert.ok(Math.abs(decoded.data[4 * i] - 0.5) <= 0.5 / 255 + 1e-7);
    assert.ok(Math.abs(own.data[4 * i] - 0.5) <= 0.5 / 256);
  }
});

test('decodeHdr reads hand-made flat and old-style RLE scanlines and divides out EXPOSURE', () => {
  const header = '#?RGBE\nFORMAT=32-bit_rle_rgbe\nEXPOSURE=2\n\n-Y 1 +X 6\n';
  // Pixel (128, 64, 0, 129) = (1, 0.5, 0) before the +0.5 reconstruction; then repeat it 4 times
  // with the old-style (1, 1, 1, n) marker; then one black pixel.
  const pixels = [128, 64, 0, 129, 1, 1, 1, 4, 0, 0, 0, 0];
  const bytes = new Uint8Array([...header].map((ch) => ch.charCodeAt(0)).concat(pixels));
  const image = decodeHdr(bytes);
  assert.deepEqual([image.width, image.height], [6, 1]);
  const step = 2 ** (129 - 136);
  for (let x = 0; x < 5; x++) {
    assert.equal(image.data[4 * x], (128.5 * step) / 2);
    assert.equal(image.data[4 * x + 1], (64.5 * step) / 2);
    assert.equal(image.data[4 * x + 2], (0.5 * step) / 2);
  }
  assert.deepEqual([...image.data.subarray(20, 24)], [0, 0, 0, 1]);
  const bad = (text: string) => new Uint8Array([...text].map((ch) => ch.charCodeAt(0)));
  const isBytes = (e: unknown) => e instanceof GpuRendererError && e.field === 'bytes';
  assert.throws(() => decodeHdr(bad('P6\n')), isBytes);
  assert.throws(() => decodeHdr(bad('#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 1 +X 1\n\0\0\0\0')), isBytes);
  assert.throws(() => decodeHdr(bad('#?RADIANCE\n\n+X 1 -Y 1\n\0\0\0\0')), isBytes); // column-major
  assert.throws(() => decodeHdr(bad('#?RADIANCE\n\n-Y 2 +X 1\n\0\0\0\0')), isBytes);
});

test('encodeHdr rejects bad images and multi-line comments with typed errors', () => {
  const isField = (field: string) => (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_OPTION' && e.field === field;
  assert.throws(() => encodeHdr({ width: 2, height: 1, data: new Float32Array(7) }), isField('image.data'));
  assert.throws(() => encodeHdr({ width: 1, height: 1, data: new Float32Array(4) }, { comment: 'a\nb' }), isField('comment'));
});

// ---- decodeRadianceHdr on files written by the test-side encoder ------------------------------------------------------------------------------

test('Radiance HDR: RLE and flat scanlines decode within RGBE precision (2^-8 of the largest channel)', () => {
  for (const rle of [true, false]) {
    const w = 37;
    const h = 5;
    const rgb = sourceImage(w, h, rle ? 1 : 2);
    const image = decodeRadianceHdr(encodeReferenceHdr(w, h, rgb, { rle }));
    assert.equal(image.width, w);
    assert.equal(image.height, h);
    assertDecodedMatches(image.data, w, h, rgb, 2 ** -8);
  }
});

test('Radiance HDR: EXPOSURE is divided out; +Y and -X orientations are flipped to top-left first', () => {
  const w = 9;
  const h = 4;
  const rgb = sourceImage(w, h, 3);
  assertDecodedMatches(decodeRadianceHdr(encodeReferenceHdr(w, h, rgb, { rle: true, exposure: 4 })).data, w, h, rgb, 2 ** -8);
  // Written bottom row first (+Y) and right to left (-X): the file's first pixel is our bottom-right.
  const flipped = new Float64Array(rgb.length);
  for (let y = 0; y < h; y++) for (let x = 0; x < w; x++) flipped.set(rgb.subarray(3 * (y * w + x), 3 * (y * w + x) + 3), 3 * ((h - 1 - y) * w + (w - 1 - x)));
  const image = decodeRadianceHdr(encodeReferenceHdr(w, h, flipped, { rle: true, orientation: `+Y ${h} -X ${w}` }));
  assertDecodedMatches(image.data, w, h, rgb, 2 ** -8);
});

test('Radiance HDR: old-style run-length repeats', () => {
  const header = new TextEncoder().encode('#?RGBE\n\n-Y 1 +X 5\n');
  // Pixel (128, 64, 32, e=129), then repeat 3 times, then one black pixel.
  const body = [128, 64, 32, 129, 1, 1, 1, 3, 0, 0, 0, 0];
  const image = decodeRadianceHdr(new Uint8Array([...header, ...body]));
  for (let x = 0; x < 4; x++) assert.deepEqual([...image.data.subarray(4 * x, 4 * x + 3)], [128.5 / 128, 64.5 / 128, 32.5 / 128]);
  assert.deepEqual([...image.data.subarray(16, 20)], [0, 0, 0, 1]);
});

function expectInvalid(fn: () => unknown): void {
  assert.throws(fn, (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_ENVIRONMENT' && e.field === 'source');
}

test('Radiance HDR: truncated and malformed files raise INVALID_ENVIRONMENT', () => {
  const w = 16;
  const h = 3;
  const good = encodeReferenceHdr(w, h, sourceImage(w, h, 4), { rle: true });
  for (const cut of [5, 30, good.length - 1, good.length - 40]) expectInvalid(() => decodeRadianceHdr(good.subarray(0, cut)));
  expectInvalid(() => decodeRadianceHdr(new TextEncoder().encode('#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 1 +X 1\n\0\0\0\0')));
  expectInvalid(() => decodeRadianceHdr(new TextEncoder().encode('#?RADIANCE\n\n+X 1 -Y 1\n\0\0\0\0')));
  expectInvalid(() => decodeRadianceHdr(new TextEncoder().encode('P6\n1 1\n255\n')));
  // An RLE scanline that claims another width.
  const bad = good.slice();
  const start = bad.indexOf(2, new TextEncoder().encode('#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 3 +X 16\n').length);
  bad[start + 3] = 15;
  expectInvalid(() => decodeRadianceHdr(bad));
});

test('limits: the side limit and the allocation limit are checked from the header, before decoding, with the caller\'s code and field', () => {
  const header = (w: number, h: number): Uint8Array => new TextEncoder().encode(`#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y ${h} +X ${w}\n${'\0'.repeat(4 * h)}`);
  // 64 x 64 texels need 64 * 64 * 20 bytes (RGBE scanlines and float texels): one byte less is refused.
  assert.throws(() => decodeHdr(header(64, 64), { maxDecodedBytes: 64 * 64 * 20 - 1 }), (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_OPTION' && e.field === 'bytes' && /maxDecodedBytes/.test(e.message));
  assert.throws(
    () => decodeRadianceHdr(header(65, 2), { field: 'environment.map', code: 'INVALID_SCENE_FILE', maxImageDimension: 64, limitName: 'map side' }),
    (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_SCENE_FILE' && e.field === 'environment.map' && /exceed the largest map side of 64/.test(e.message),
  );
  // Within both limits a black image (every exponent byte 0) decodes.
  const w = 8;
  const h = 2;
  const ok = decodeRadianceHdr(new Uint8Array([...new TextEncoder().encode(`#?RADIANCE\n\n-Y ${h} +X ${w}\n`), ...new Uint8Array(4 * w * h)]), { maxImageDimension: 8, maxDecodedBytes: w * h * 20 });
  assert.deepEqual([ok.width, ok.height, ok.data[0], ok.data[3]], [w, h, 0, 1]);
});
