/**
 * Environment-map seeds: Radiance .hdr files in each scanline encoding (flat, old-style repeats,
 * new-style per-channel RLE), OpenEXR files written here (scanline NONE and ZIP, half and float;
 * tiled NONE), and DWAB-compressed CC0 maps from @pmndrs/assets (real files from a real writer).
 */
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { zlibSync } from 'fflate';

export interface EnvSeed {
  name: string;
  bytes: Uint8Array;
}

const encoder = new TextEncoder();

function hdr(width: number, height: number, encoding: 'flat' | 'old-rle' | 'new-rle'): Uint8Array {
  const out: number[] = [...encoder.encode(`#?RADIANCE\nFORMAT=32-bit_rle_rgbe\nEXPOSURE=2\n\n-Y ${height} +X ${width}\n`)];
  for (let y = 0; y < height; y++) {
    const texel = (x: number): number[] => [(x * 16 + y * 8) & 0xff, 128, (y * 30) & 0xff, 128 + (x % 3)];
    if (encoding === 'new-rle') {
      out.push(2, 2, width >> 8, width & 0xff);
      for (let c = 0; c < 4; c++) {
        // One literal run, then one repeat run of the channel's last value.
        const literal = Math.ceil(width / 2);
        out.push(literal);
        for (let x = 0; x < literal; x++) out.push(texel(x)[c]!);
        out.push(128 + (width - literal), texel(literal)[c]!);
      }
    } else if (encoding === 'old-rle') {
      out.push(...texel(0), 1, 1, 1, width - 1);
    } else {
      for (let x = 0; x < width; x++) out.push(...texel(x));
    }
  }
  return new Uint8Array(out);
}

function exr(width: number, height: number, options: { pixel: 'half' | 'float'; compression: 'none' | 'zip'; tiled?: boolean }): Uint8Array {
  const bytes: number[] = [];
  const u8 = (...v: number[]): void => void bytes.push(...v);
  const i32 = (v: number): void => u8(v & 0xff, (v >> 8) & 0xff, (v >> 16) & 0xff, (v >>> 24) & 0xff);
  const f32 = (v: number): void => u8(...new Uint8Array(new Float32Array([v]).buffer));
  const str = (s: string): void => u8(...encoder.encode(s), 0);
  const attr = (name: string, type: string, size: number, write: () => void): void => {
    str(name);
    str(type);
    i32(size);
    write();
  };
  const channels = ['B', 'G', 'R'];
  const size = options.pixel === 'half' ? 2 : 4;
  u8(0x76, 0x2f, 0x31, 0x01, 2, options.tiled ? 2 : 0, 0, 0);
  attr('channels', 'chlist', channels.length * 18 + 1, () => {
    for (const c of channels) {
      str(c);
      i32(options.pixel === 'half' ? 1 : 2);
      u8(0, 0, 0, 0);
      i32(1);
      i32(1);
    }
    u8(0);
  });
  attr('compression', 'compression', 1, () => u8(options.compression === 'zip' ? 3 : 0));
  attr('dataWindow', 'box2i', 16, () => [0, 0, width - 1, height - 1].forEach(i32));
  attr('displayWindow', 'box2i', 16, () => [0, 0, width - 1, height - 1].forEach(i32));
  attr('lineOrder', 'lineOrder', 1, () => u8(0));
  attr('pixelAspectRatio', 'float', 4, () => f32(1));
  attr('screenWindowCenter', 'v2f', 8, () => (f32(0), f32(0)));
  attr('screenWindowWidth', 'float', 4, () => f32(1));
  if (options.tiled) attr('tiles', 'tiledesc', 9, () => (i32(4), i32(4), u8(0)));
  u8(0);
  const value = (x: number, y: number, c: number): number => 0.1 + x * 0.05 + y * 0.1 + c;
  const encodeRows = (x0: number, columns: number, y0: number, lines: number): Uint8Array => {
    const raw = new Uint8Array(lines * channels.length * columns * size);
    const view = new DataView(raw.buffer);
    let o = 0;
    for (let y = y0; y < y0 + lines; y++) {
      for (let c = 0; c < channels.length; c++) {
        for (let x = x0; x < x0 + columns; x++) {
          if (size === 2) view.setFloat16(o, value(x, y, c), true);
          else view.setFloat32(o, value(x, y, c), true);
          o += size;
        }
      }
    }
    if (options.compression !== 'zip') return raw;
    // OpenEXR ZIP: even/odd byte split, byte-delta predictor, zlib (ImfZip.cpp).
    const t = new Uint8Array(raw.length);
    const half = (raw.length + 1) >> 1;
    for (let k = 0; k < raw.length; k++) t[(k & 1) === 0 ? k >> 1 : half + (k >> 1)] = raw[k]!;
    for (let k = t.length - 1; k > 0; k--) t[k] = (t[k]! - t[k - 1]! + 128 + 256) & 0xff;
    const zipped = zlibSync(t);
    return zipped.length < raw.length ? zipped : raw;
  };
  const chunks: Array<{ header: number[]; data: Uint8Array }> = [];
  if (options.tiled) {
    for (let ty = 0; ty < Math.ceil(height / 4); ty++) {
      for (let tx = 0; tx < Math.ceil(width / 4); tx++) {
        const data = encodeRows(tx * 4, Math.min(4, width - tx * 4), ty * 4, Math.min(4, height - ty * 4));
        chunks.push({ header: [tx, ty, 0, 0, data.length], data });
      }
    }
  } else {
    const lines = options.compression === 'zip' ? 16 : 1;
    for (let y0 = 0; y0 < height; y0 += lines) {
      const data = encodeRows(0, width, y0, Math.min(lines, height - y0));
      chunks.push({ header: [y0, data.length], data });
    }
  }
  const tableAt = bytes.length;
  for (let k = 0; k < chunks.length * 8; k++) u8(0);
  const offsets: number[] = [];
  for (const chunk of chunks) {
    offsets.push(bytes.length);
    chunk.header.forEach(i32);
    u8(...chunk.data);
  }
  const out = new Uint8Array(bytes);
  const table = new DataView(out.buffer, tableAt, chunks.length * 8);
  offsets.forEach((off, k) => table.setBigUint64(8 * k, BigInt(off), true));
  return out;
}

/** The DWAB maps of @pmndrs/assets (a data: URI per module), a few of them. */
function pmndrs(names: readonly string[]): EnvSeed[] {
  const require = createRequire(import.meta.url);
  return names.map((name) => {
    const text = readFileSync(require.resolve(`@pmndrs/assets/hdri/${name}.exr.js`), 'utf8');
    const base64 = /base64,([^'"]+)/.exec(text)![1]!;
    return { name: `${name}.exr (DWAB)`, bytes: new Uint8Array(Buffer.from(base64, 'base64')) };
  });
}

export function buildEnvCorpus(): EnvSeed[] {
  return [
    { name: 'flat.hdr', bytes: hdr(6, 4, 'flat') },
    { name: 'old-rle.hdr', bytes: hdr(12, 6, 'old-rle') },
    { name: 'new-rle.hdr', bytes: hdr(16, 8, 'new-rle') },
    { name: 'none-float.exr', bytes: exr(8, 4, { pixel: 'float', compression: 'none' }) },
    { name: 'zip-half.exr', bytes: exr(16, 20, { pixel: 'half', compression: 'zip' }) },
    { name: 'tiled-half.exr', bytes: exr(10, 6, { pixel: 'half', compression: 'none', tiled: true }) },
    ...pmndrs(['studio', 'lab', 'sunset']),
  ];
}
