// Test-side encoders of Radiance HDR and OpenEXR files, written from the format descriptions
// independently of src/io/images, and the fixtures the decoder and loader tests share.
import assert from 'node:assert/strict';
import { deflateSync } from 'node:zlib';
import { rng } from '../../helpers/random.ts';


/** Float RGB -> RGBE (Ward's float2rgbe: mantissa = floor(c * 256 / 2^e), e from frexp(max)). */
export function toRgbe(r: number, g: number, b: number): [number, number, number, number] {
  const v = Math.max(r, g, b);
  if (v < 1e-32) return [0, 0, 0, 0];
  const e = Math.floor(Math.log2(v)) + 1; // v = m * 2^e with m in [0.5, 1)
  const scale = 256 / 2 ** e;
  return [Math.floor(r * scale), Math.floor(g * scale), Math.floor(b * scale), e + 128];
}

/** New-style RLE of one channel of one scanline (runs of >= 3 equal bytes, else literals). */
export function rleChannel(values: number[]): number[] {
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

export function encodeHdr(width: number, height: number, rgb: Float64Array, opts: { rle: boolean; orientation?: string; exposure?: number }): Uint8Array {
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
export function sourceImage(width: number, height: number, seed: number): Float64Array {
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

export function assertDecodedMatches(data: Float32Array, width: number, height: number, rgb: Float64Array, relTolerance: number): void {
  for (let t = 0; t < width * height; t++) {
    const max = Math.max(rgb[3 * t]!, rgb[3 * t + 1]!, rgb[3 * t + 2]!);
    for (let c = 0; c < 3; c++) {
      const err = Math.abs(data[4 * t + c]! - rgb[3 * t + c]!);
      assert.ok(err <= relTolerance * max + 1e-30, `texel ${t} channel ${c}: ${data[4 * t + c]} vs ${rgb[3 * t + c]}`);
    }
    assert.equal(data[4 * t + 3], 1);
  }
}


export type PixelType = 'half' | 'float';

/** A single-part scanline OpenEXR file with channels B, G, R (and A), written by this test. */
export function encodeExr(width: number, height: number, rgb: Float64Array, pixel: PixelType, compression: 'none' | 'zip'): Uint8Array {
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
export function exrSource(width: number, height: number): Float64Array {
  const rgb = new Float64Array(width * height * 3);
  for (let y = 0; y < height; y++) for (let x = 0; x < width; x++) rgb.set([x < 8 ? 2 : x * 0.37 + y, 0.125 * (y % 3), x === 5 ? 30000 : 1 / (1 + x)], 3 * (y * width + x));
  return rgb;
}
