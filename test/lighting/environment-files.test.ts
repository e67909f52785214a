import { test } from 'node:test';
import assert from 'node:assert/strict';
import { deflateSync } from 'node:zlib';
import { mkdtempSync, writeFileSync, rmSync } from 'node:fs';
import { createServer } from 'node:http';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { decodeRadianceHdr } from '../../src/lighting/radiance-hdr.ts';
import { decodeOpenExr } from '../../src/lighting/openexr.ts';
import { loadEnvironmentMap } from '../../src/lighting/load-environment-map.ts';
import { rng } from './helpers.ts';

// ---- test-side encoders ------------------------------------------------------------------------

/** Float RGB -> RGBE (Ward's float2rgbe: mantissa = floor(c * 256 / 2^e), e from frexp(max)). */
function toRgbe(r: number, g: number, b: number): [number, number, number, number] {
  const v = Math.max(r, g, b);
  if (v < 1e-32) return [0, 0, 0, 0];
  const e = Math.floor(Math.log2(v)) + 1; // v = m * 2^e with m in [0.5, 1)
  const scale = 256 / 2 ** e;
  return [Math.floor(r * scale), Math.floor(g * scale), Math.floor(b * scale), e + 128];
}

/** New-style RLE of one channel of one scanline (runs of >= 3 equal bytes, else literals). */
function rleChannel(values: number[]): number[] {
  const out: number[] = [];
  let i = 0;
  while (i < values.length) {
    let run = 1;
    while (i + run < values.length && run < 127 && values[i + run] === values[i]) run++;
    if (run >= 3) {
      out.push(128 + run, values[i]!);
      i += run;
      continue;
    }
    const start = i;
    while (i < values.length && i - start < 128) {
      if (i + 2 < values.length && values[i] === values[i + 1] && values[i] === values[i + 2]) break;
      i++;
    }
    out.push(i - start, ...values.slice(start, i));
  }
  return out;
}

function encodeHdr(width: number, height: number, rgb: Float64Array, opts: { rle: boolean; orientation?: string; exposure?: number }): Uint8Array {
  const header = `#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n${opts.exposure ? `EXPOSURE=${opts.exposure}\n` : ''}\n${opts.orientation ?? `-Y ${height} +X ${width}`}\n`;
  const bytes: number[] = [...new TextEncoder().encode(header)];
  for (let y = 0; y < height; y++) {
    const px: number[][] = [];
    for (let x = 0; x < width; x++) {
      const k = 3 * (y * width + x);
      px.push(toRgbe(rgb[k]! * (opts.exposure ?? 1), rgb[k + 1]! * (opts.exposure ?? 1), rgb[k + 2]! * (opts.exposure ?? 1)));
    }
    if (opts.rle) {
      bytes.push(2, 2, width >> 8, width & 0xff);
      for (let c = 0; c < 4; c++) bytes.push(...rleChannel(px.map((p) => p[c]!)));
    } else {
      for (const p of px) bytes.push(...p);
    }
  }
  return new Uint8Array(bytes);
}

/** Smooth, bright, with exact repeats (so runs appear) and black texels. */
function sourceImage(width: number, height: number, seed: number): Float64Array {
  const random = rng(seed);
  const rgb = new Float64Array(width * height * 3);
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const k = 3 * (y * width + x);
      if (x < 4) rgb.set([0.25, 0.5, 1], k);
      else if (x === width - 1) rgb.set([0, 0, 0], k);
      else rgb.set([random() * 50, random() * 0.02, 1000 * random() + 1], k);
    }
  }
  return rgb;
}

function assertDecodedMatches(data: Float32Array, width: number, height: number, rgb: Float64Array, relTolerance: number): void {
  for (let t = 0; t < width * height; t++) {
    const max = Math.max(rgb[3 * t]!, rgb[3 * t + 1]!, rgb[3 * t + 2]!);
    for (let c = 0; c < 3; c++) {
      const err = Math.abs(data[4 * t + c]! - rgb[3 * t + c]!);
      assert.ok(err <= relTolerance * max + 1e-30, `texel ${t} channel ${c}: ${data[4 * t + c]} vs ${rgb[3 * t + c]}`);
    }
    assert.equal(data[4 * t + 3], 1);
  }
}

// ---- Radiance HDR ------------------------------------------------------------------------------

test('Radiance HDR: RLE and flat scanlines decode within RGBE precision (2^-8 of the largest channel)', () => {
  for (const rle of [true, false]) {
    const w = 37;
    const h = 5;
    const rgb = sourceImage(w, h, rle ? 1 : 2);
    const image = decodeRadianceHdr(encodeHdr(w, h, rgb, { rle }));
    assert.equal(image.width, w);
    assert.equal(image.height, h);
    assertDecodedMatches(image.data, w, h, rgb, 2 ** -8);
  }
});

test('Radiance HDR: EXPOSURE is divided out; +Y and -X orientations are flipped to top-left first', () => {
  const w = 9;
  const h = 4;
  const rgb = sourceImage(w, h, 3);
  assertDecodedMatches(decodeRadianceHdr(encodeHdr(w, h, rgb, { rle: true, exposure: 4 })).data, w, h, rgb, 2 ** -8);
  // Written bottom row first (+Y) and right to left (-X): the file's first pixel is our bottom-right.
  const flipped = new Float64Array(rgb.length);
  for (let y = 0; y < h; y++) for (let x = 0; x < w; x++) flipped.set(rgb.subarray(3 * (y * w + x), 3 * (y * w + x) + 3), 3 * ((h - 1 - y) * w + (w - 1 - x)));
  const image = decodeRadianceHdr(encodeHdr(w, h, flipped, { rle: true, orientation: `+Y ${h} -X ${w}` }));
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
  const good = encodeHdr(w, h, sourceImage(w, h, 4), { rle: true });
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

// ---- OpenEXR -----------------------------------------------------------------------------------

type PixelType = 'half' | 'float';

/** A single-part scanline OpenEXR file with channels B, G, R (and A), written by this test. */
function encodeExr(width: number, height: number, rgb: Float64Array, pixel: PixelType, compression: 'none' | 'zip'): Uint8Array {
  const bytes: number[] = [];
  const u8 = (...v: number[]) => bytes.push(...v);
  const i32 = (v: number) => u8(v & 0xff, (v >> 8) & 0xff, (v >> 16) & 0xff, (v >>> 24) & 0xff);
  const f32 = (v: number) => u8(...new Uint8Array(new Float32Array([v]).buffer));
  const str = (s: string) => u8(...new TextEncoder().encode(s), 0);
  const attr = (name: string, type: string, size: number, write: () => void) => {
    str(name);
    str(type);
    i32(size);
    write();
  };
  const channels = ['A', 'B', 'G', 'R'];
  const typeCode = pixel === 'half' ? 1 : 2;
  u8(0x76, 0x2f, 0x31, 0x01, 2, 0, 0, 0);
  attr('channels', 'chlist', channels.length * 18 + 1, () => {
    for (const c of channels) {
      str(c);
      i32(typeCode);
      u8(0, 0, 0, 0);
      i32(1);
      i32(1);
    }
    u8(0);
  });
  attr('compression', 'compression', 1, () => u8(compression === 'zip' ? 3 : 0));
  attr('dataWindow', 'box2i', 16, () => [0, 0, width - 1, height - 1].forEach(i32));
  attr('displayWindow', 'box2i', 16, () => [0, 0, width - 1, height - 1].forEach(i32));
  attr('lineOrder', 'lineOrder', 1, () => u8(0));
  attr('pixelAspectRatio', 'float', 4, () => f32(1));
  attr('screenWindowCenter', 'v2f', 8, () => (f32(0), f32(0)));
  attr('screenWindowWidth', 'float', 4, () => f32(1));
  u8(0);
  const linesPerChunk = compression === 'zip' ? 16 : 1;
  const chunkCount = Math.ceil(height / linesPerChunk);
  const tableAt = bytes.length;
  for (let k = 0; k < chunkCount * 8; k++) u8(0);
  const offsets: number[] = [];
  const size = pixel === 'half' ? 2 : 4;
  for (let chunk = 0; chunk < chunkCount; chunk++) {
    const y0 = chunk * linesPerChunk;
    const lines = Math.min(linesPerChunk, height - y0);
    const raw = new Uint8Array(lines * channels.length * width * size);
    const view = new DataView(raw.buffer);
    let o = 0;
    for (let y = y0; y < y0 + lines; y++) {
      for (const c of channels) {
        for (let x = 0; x < width; x++) {
          const v = c === 'A' ? 1 : rgb[3 * (y * width + x) + { R: 0, G: 1, B: 2 }[c]!]!;
          if (pixel === 'half') view.setUint16(o, new Uint16Array(new Float16Array([v]).buffer)[0]!, true);
          else view.setFloat32(o, v, true);
          o += size;
        }
      }
    }
    let data: Uint8Array = raw;
    if (compression === 'zip') {
      // OpenEXR's ZIP: split even/odd bytes, byte-delta predictor, then zlib (ImfZip.cpp).
      const t = new Uint8Array(raw.length);
      const half = (raw.length + 1) >> 1;
      for (let k = 0; k < raw.length; k++) t[(k & 1) === 0 ? k >> 1 : half + (k >> 1)] = raw[k]!;
      for (let k = t.length - 1; k > 0; k--) t[k] = (t[k]! - t[k - 1]! + 128 + 256) & 0xff;
      data = deflateSync(t);
      assert.ok(data.length < raw.length, 'test data must compress, or OpenEXR would store it raw');
    }
    offsets.push(bytes.length);
    i32(y0);
    i32(data.length);
    u8(...data);
  }
  const out = new Uint8Array(bytes);
  const table = new DataView(out.buffer, tableAt, chunkCount * 8);
  offsets.forEach((off, k) => table.setBigUint64(8 * k, BigInt(off), true));
  return out;
}

/** Values that compress (repeats) and exercise the range. */
function exrSource(width: number, height: number): Float64Array {
  const rgb = new Float64Array(width * height * 3);
  for (let y = 0; y < height; y++) for (let x = 0; x < width; x++) rgb.set([x < 8 ? 2 : x * 0.37 + y, 0.125 * (y % 3), x === 5 ? 30000 : 1 / (1 + x)], 3 * (y * width + x));
  return rgb;
}

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

test('OpenEXR: truncated or corrupt files raise INVALID_ENVIRONMENT', async () => {
  const good = encodeExr(16, 20, exrSource(16, 20), 'half', 'zip');
  for (const cut of [3, 40, good.length - 10, Math.floor(good.length / 2)]) {
    await assert.rejects(loadEnvironmentMap(good.subarray(0, cut)), (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_ENVIRONMENT');
  }
});

// ---- loadEnvironmentMap --------------------------------------------------------------------------

test('loadEnvironmentMap reads bytes, paths, file URLs and http URLs, and validates the texels', async () => {
  const w = 12;
  const h = 6;
  const rgb = sourceImage(w, h, 9);
  const hdr = encodeHdr(w, h, rgb, { rle: true });
  const fromBytes = await loadEnvironmentMap(hdr, { intensity: 2, rotationRadians: 0.5 });
  assert.equal(fromBytes.intensity, 2);
  assert.equal(fromBytes.rotationRadians, 0.5);
  assertDecodedMatches(fromBytes.data, w, h, rgb, 2 ** -8);
  const exr = encodeExr(w, h, exrSource(w, h), 'float', 'none');
  assert.equal((await loadEnvironmentMap(exr.buffer as ArrayBuffer)).width, w);

  const dir = mkdtempSync(join(tmpdir(), 'env-'));
  try {
    const path = join(dir, 'sky.hdr');
    writeFileSync(path, hdr);
    assert.deepEqual((await loadEnvironmentMap(path)).data, fromBytes.data);
    assert.deepEqual((await loadEnvironmentMap(pathToFileURL(path))).data, fromBytes.data);
    await assert.rejects(loadEnvironmentMap(join(dir, 'missing.hdr')), (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_ENVIRONMENT');
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }

  const server = createServer((req, res) => {
    if (req.url === '/sky.exr') res.end(exr);
    else res.writeHead(404).end();
  });
  await new Promise<void>((resolve) => server.listen(0, '127.0.0.1', resolve));
  try {
    const { port } = server.address() as { port: number };
    const fetched = await loadEnvironmentMap(`http://127.0.0.1:${port}/sky.exr`);
    assert.equal(fetched.width, w);
    await assert.rejects(loadEnvironmentMap(new URL(`http://127.0.0.1:${port}/none.hdr`)), /HTTP 404/);
  } finally {
    server.close();
  }

  // Negative radiance is legal in EXR but not in an environment map: the texel is named.
  const negative = exrSource(w, h);
  negative[3 * 7 + 1] = -1;
  await assert.rejects(loadEnvironmentMap(encodeExr(w, h, negative, 'float', 'none')), (e: unknown) => e instanceof GpuRendererError && e.field === 'source.data[29]');
  await assert.rejects(loadEnvironmentMap(new Uint8Array([1, 2, 3, 4, 5])), /not a Radiance/);
  await assert.rejects(loadEnvironmentMap(42 as unknown as string), (e: unknown) => e instanceof GpuRendererError && e.field === 'source');
});

test("negativeTexels: 'error' refuses a map with a channel below zero (lossy EXR ringing); 'zero' sets it to 0 and reports it", async () => {
  const w = 8;
  const h = 4;
  const rgb = exrSource(w, h);
  // Two negative channels, as DWA compression leaves beside bright texels.
  rgb[3 * 9 + 1] = -0.25;
  rgb[3 * 20 + 2] = -1.5;
  const exr = encodeExr(w, h, rgb, 'float', 'none');
  await assert.rejects(loadEnvironmentMap(exr), (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_ENVIRONMENT' && e.field === 'source.data[37]');
  let report: { channels: number; addedEnergyFraction: number } | undefined;
  const map = await loadEnvironmentMap(exr, { negativeTexels: 'zero', onNegativeTexels: (r) => (report = r) });
  assert.equal(map.data[4 * 9 + 1], 0);
  assert.equal(map.data[4 * 20 + 2], 0);
  let kept = 0;
  for (const v of rgb) if (v >= 0) kept += v;
  assert.equal(report?.channels, 2);
  assert.ok(Math.abs(report!.addedEnergyFraction - 1.75 / kept) < 1e-6 * (1.75 / kept), `added ${report!.addedEnergyFraction} vs ${1.75 / kept}`);
  // Every other channel is decoded as it is.
  for (let t = 0; t < w * h; t++) for (let c = 0; c < 3; c++) if (rgb[3 * t + c]! >= 0) assert.ok(Math.abs(map.data[4 * t + c]! - rgb[3 * t + c]!) <= 2 ** -23 * Math.abs(rgb[3 * t + c]!));
  await assert.rejects(loadEnvironmentMap(exr, { negativeTexels: 'clamp' as never }), (e: unknown) => e instanceof GpuRendererError && e.field === 'negativeTexels');
});
