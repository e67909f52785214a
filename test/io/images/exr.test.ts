import { test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtemp, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { encodeExr, type ExrCompression, type ExrPixelType } from '../../../src/io/images/exr-encode.ts';
import { GpuRendererError } from '../../../src/errors/gpu-renderer-error.ts';
import { rng } from '../../helpers/random.ts';
import { openExrUnavailable, readExrWithOpenExr, readExrWithThree } from './independent-readers.ts';

function radiance(width: number, height: number, seed: number): Float32Array {
  const rand = rng(seed);
  const data = new Float32Array(width * height * 4);
  for (let i = 0; i < data.length; i++) {
    // Smooth gradients plus a wide dynamic range (1e-4 .. 1e4) so half rounding is exercised.
    data[i] = i % 4 === 3 ? (rand() < 0.2 ? 0.5 : 1) : Math.pow(10, -4 + 8 * rand()) * (rand() < 0.05 ? 0 : 1);
  }
  return data;
}

/** What a reader must return for a value stored with `pixelType`. */
const stored = (v: number, pixelType: ExrPixelType): number => (pixelType === 'half' ? Math.f16round(v) : Math.fround(v));

const compressions: ExrCompression[] = ['none', 'zips', 'zip'];
const pixelTypes: ExrPixelType[] = ['half', 'float'];

test('three.js EXRLoader reads our beauty back exactly (every compression and pixel type, odd sizes, partial ZIP blocks)', () => {
  for (const [width, height] of [
    [1, 1],
    [5, 37],
    [17, 16],
  ]) {
    const data = radiance(width, height, width * 100 + height);
    for (const compression of compressions) {
      for (const pixelType of pixelTypes) {
        const decoded = readExrWithThree(encodeExr({ width, height, data }, { compression, pixelType }));
        assert.deepEqual([decoded.width, decoded.height], [width, height]);
        for (let i = 0; i < data.length; i++) {
          assert.equal(decoded.data[i], stored(data[i], pixelType), `${width}x${height} ${compression} ${pixelType} index ${i}`);
        }
      }
    }
  }
});

test('header attributes as three.js parses them: channels sorted, types, compression, windows, line order, pixel aspect, screen window', () => {
  const width = 6;
  const height = 3;
  const bytes = encodeExr(
    { width, height, data: radiance(width, height, 3) },
    { pixelType: 'half', compression: 'zip', aovs: { normal: new Float32Array(width * height * 3) } },
  );
  const { header } = readExrWithThree(bytes);
  const channels = header.channels as { name: string; pixelType: number; pLinear: number; xSampling: number; ySampling: number }[];
  assert.deepEqual(
    channels.map((c) => c.name),
    ['A', 'B', 'G', 'R', 'normal.X', 'normal.Y', 'normal.Z'],
  );
  assert.ok(channels.every((c) => c.pixelType === 1 && c.pLinear === 0 && c.xSampling === 1 && c.ySampling === 1));
  assert.equal(header.compression, 'ZIP_COMPRESSION');
  assert.deepEqual(header.dataWindow, { xMin: 0, yMin: 0, xMax: width - 1, yMax: height - 1 });
  assert.deepEqual(header.displayWindow, { xMin: 0, yMin: 0, xMax: width - 1, yMax: height - 1 });
  assert.equal(header.lineOrder, 'INCREASING_Y');
  assert.equal(header.pixelAspectRatio, 1);
  assert.deepEqual(header.screenWindowCenter, [0, 0]);
  assert.equal(header.screenWindowWidth, 1);
  // Magic number and version field (2, single-part scanline, short names).
  const view = new DataView(bytes.buffer);
  assert.equal(view.getInt32(0, true), 20000630);
  assert.equal(view.getInt32(4, true), 2);
});

test('layers interleaved between the beauty channels (C.X sorts between B and G) leave the beauty intact', () => {
  // If per-scanline channel offsets were wrong, G and R (stored after C.X) would come back garbled.
  const width = 9;
  const height = 20;
  const data = radiance(width, height, 5);
  const layer = new Float32Array(width * height).map((_, i) => i * 0.25);
  for (const compression of compressions) {
    for (const pixelType of pixelTypes) {
      const bytes = encodeExr({ width, height, data }, { compression, pixelType, layers: [{ name: 'C', channels: ['X'], data: layer, pixelType: 'float' }] });
      const decoded = readExrWithThree(bytes);
      assert.deepEqual(
        (decoded.header.channels as { name: string }[]).map((c) => c.name),
        ['A', 'B', 'C.X', 'G', 'R'],
      );
      for (let i = 0; i < data.length; i++) assert.equal(decoded.data[i], stored(data[i], pixelType), `${compression} ${pixelType} ${i}`);
    }
  }
});

test('ZIP chunks that do not shrink are stored raw, and the offset table points at every chunk in order', () => {
  // Random float bit patterns do not compress; the file must then hold the raw scanlines.
  const width = 7;
  const height = 33;
  const rand = rng(9);
  const bits = new Uint32Array(width * height * 4).map(() => ((rand() * 0x3f800000) >>> 0) & 0x3f7fffff);
  const data = new Float32Array(bits.buffer);
  const bytes = encodeExr({ width, height, data }, { compression: 'zip', pixelType: 'float' });
  const decoded = readExrWithThree(bytes);
  for (let i = 0; i < data.length; i++) assert.equal(decoded.data[i], data[i]);
  // Walk the offset table: each entry points at (y, size, payload) and chunks are contiguous.
  const view = new DataView(bytes.buffer, bytes.byteOffset);
  const chunks = Math.ceil(height / 16);
  const headerEnd = findHeaderEnd(bytes);
  let expected = headerEnd + 8 * chunks;
  let rawChunks = 0;
  for (let c = 0; c < chunks; c++) {
    const offset = Number(view.getBigUint64(headerEnd + 8 * c, true));
    assert.equal(offset, expected, `chunk ${c}`);
    assert.equal(view.getInt32(offset, true), 16 * c);
    const size = view.getInt32(offset + 4, true);
    const lines = Math.min(16, height - 16 * c);
    if (size === lines * width * 4 * 4) rawChunks++;
    expected = offset + 8 + size;
  }
  assert.equal(expected, bytes.length);
  assert.ok(rawChunks >= 1, 'random data should have produced at least one raw chunk');
});

/** Byte after the header's terminating NUL: attributes are name\0 type\0 size value, then \0. */
function findHeaderEnd(bytes: Uint8Array): number {
  const view = new DataView(bytes.buffer, bytes.byteOffset);
  let pos = 8;
  const cString = (): string => {
    const start = pos;
    while (bytes[pos] !== 0) pos++;
    return String.fromCharCode(...bytes.subarray(start, pos++));
  };
  for (;;) {
    if (cString() === '') return pos;
    cString();
    const size = view.getInt32(pos, true);
    pos += 4 + size;
  }
}

test('typed errors for bad options and data', () => {
  const image = { width: 2, height: 2, data: new Float32Array(16) };
  const isField = (field: string) => (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_OPTION' && e.field === field;
  assert.throws(() => encodeExr(image, { compression: 'piz' as never }), isField('compression'));
  assert.throws(() => encodeExr(image, { pixelType: 'uint' as never }), isField('pixelType'));
  assert.throws(() => encodeExr(image, { aovs: { shadow: new Float32Array(12) } as never }), isField('aovs.shadow'));
  assert.throws(() => encodeExr(image, { aovs: { albedo: new Float32Array(8) } }), isField('aovs.albedo'));
  assert.throws(() => encodeExr(image, { aovs: { depth: new Float32Array(5) } }), isField('aovs.depth'));
  assert.throws(() => encodeExr(image, { layers: [{ name: 'caf\u00e9', channels: ['R'], data: new Float32Array(4) }] }), isField('layers[0].name'));
  assert.throws(() => encodeExr(image, { layers: [{ name: 'x', channels: [], data: new Float32Array(4) }] }), isField('layers[0].channels'));
  assert.throws(() => encodeExr(image, { layers: [{ name: 'albedo', channels: ['R'], data: new Float32Array(4) }], aovs: { albedo: new Float32Array(12) } }), isField('layers'));
  assert.throws(() => encodeExr({ width: 2, height: 2, data: new Float32Array(15) }), isField('image.data'));
  assert.throws(() => encodeExr({ width: 0, height: 2, data: new Float32Array(0) }), isField('image.width'));
});

const openExrSkip = openExrUnavailable();

test('the reference OpenEXR library reads every channel, AOV and layer back, with the header we wrote', { skip: openExrSkip }, async () => {
  const dir = await mkdtemp(join(tmpdir(), 'gpu-renderer-exr-'));
  try {
    const width = 11;
    const height = 19;
    const data = radiance(width, height, 21);
    const albedo = new Float32Array(width * height * 4).map((_, i) => (i % 4) * 0.2 + (i >> 2) / (width * height));
    const normal = new Float32Array(width * height * 3).map((_, i) => Math.sin(i * 0.37));
    const depth = new Float32Array(width * height).map((_, i) => 1 + i * 3.5);
    const longName = 'a_layer_name_longer_than_thirty_one_bytes';
    const custom = new Float32Array(width * height * 2).map((_, i) => -i);
    for (const compression of compressions) {
      for (const pixelType of pixelTypes) {
        const bytes = encodeExr(
          { width, height, data },
          { compression, pixelType, aovs: { albedo, normal, depth }, layers: [{ name: longName, channels: ['U', 'V'], data: custom, pixelType: 'float' }] },
        );
        const path = join(dir, `${compression}-${pixelType}.exr`);
        await writeFile(path, bytes);
        const dump = readExrWithOpenExr(path);
        const expected: Record<string, { source: Float32Array; stride: number; component: number; type: ExrPixelType }> = {};
        ['R', 'G', 'B', 'A'].forEach((c, k) => (expected[c] = { source: data, stride: 4, component: k, type: pixelType }));
        ['R', 'G', 'B'].forEach((c, k) => (expected[`albedo.${c}`] = { source: albedo, stride: 4, component: k, type: pixelType }));
        ['X', 'Y', 'Z'].forEach((c, k) => (expected[`normal.${c}`] = { source: normal, stride: 3, component: k, type: pixelType }));
        expected['depth.Z'] = { source: depth, stride: 1, component: 0, type: pixelType };
        ['U', 'V'].forEach((c, k) => (expected[`${longName}.${c}`] = { source: custom, stride: 2, component: k, type: 'float' }));
        assert.deepEqual(Object.keys(dump.channels).sort(), Object.keys(expected).sort());
        for (const [name, want] of Object.entries(expected)) {
          const got = dump.channels[name];
          assert.equal(got.type, want.type === 'half' ? 'float16' : 'float32', name);
          assert.deepEqual(got.shape, [height, width], name);
          for (let p = 0; p < width * height; p++) {
            assert.equal(got.values[p], stored(want.source[p * want.stride + want.component], want.type), `${compression} ${pixelType} ${name} pixel ${p}`);
          }
        }
        assert.deepEqual(dump.header.dataWindow, [
          [0, 0],
          [width - 1, height - 1],
        ]);
        assert.deepEqual(dump.header.displayWindow, dump.header.dataWindow);
        assert.equal(dump.header.lineOrder, 'LineOrder.INCREASING_Y');
        assert.equal(dump.header.compression, { none: 'Compression.NO_COMPRESSION', zips: 'Compression.ZIPS_COMPRESSION', zip: 'Compression.ZIP_COMPRESSION' }[compression]);
        assert.equal(dump.header.pixelAspectRatio, 1);
        assert.deepEqual(dump.header.screenWindowCenter, [0, 0]);
        assert.equal(dump.header.screenWindowWidth, 1);
      }
    }
  } finally {
    await rm(dir, { recursive: true, force: true });
  }
});
