/**
 * A minimal OpenEXR reader for the CLI tests, written from the file layout specification
 * (openexr.com, "OpenEXR File Layout"), independently of src/io/images/exr-encode.ts: single-part
 * scanline files, NO / ZIPS / ZIP compression, HALF and FLOAT channels of any name.
 */
import { unzlibSync } from 'fflate';

export interface ExrChannels {
  width: number;
  height: number;
  /** Every channel by its full name ('R', 'albedo.G', ...), top row first. */
  channels: Record<string, { type: 'half' | 'float'; values: Float32Array }>;
}

function halfToFloat(h: number): number {
  const sign = h & 0x8000 ? -1 : 1;
  const exponent = (h >> 10) & 0x1f;
  const fraction = h & 0x3ff;
  if (exponent === 0) return sign * fraction * 2 ** -24;
  if (exponent === 31) return fraction === 0 ? sign * Infinity : Number.NaN;
  return sign * (1 + fraction / 1024) * 2 ** (exponent - 15);
}

export function readExrChannels(bytes: Uint8Array): ExrChannels {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  if (view.getInt32(0, true) !== 20000630) throw new Error('not an OpenEXR file');
  let at = 8;
  const cString = (): string => {
    let end = at;
    while (bytes[end] !== 0) end++;
    const s = new TextDecoder().decode(bytes.subarray(at, end));
    at = end + 1;
    return s;
  };
  const list: { name: string; type: 'half' | 'float' }[] = [];
  let compression = -1;
  let box = [0, 0, 0, 0];
  for (;;) {
    const name = cString();
    if (name === '') break;
    cString(); // type
    const size = view.getInt32(at, true);
    at += 4;
    const start = at;
    if (name === 'channels') {
      for (;;) {
        const channel = cString();
        if (channel === '') break;
        const type = view.getInt32(at, true);
        if (type !== 1 && type !== 2) throw new Error(`pixel type ${type}`);
        list.push({ name: channel, type: type === 1 ? 'half' : 'float' });
        at += 16;
      }
    } else if (name === 'compression') {
      compression = bytes[at]!;
    } else if (name === 'dataWindow') {
      box = [0, 1, 2, 3].map((k) => view.getInt32(at + 4 * k, true));
    }
    at = start + size;
  }
  const width = box[2]! - box[0]! + 1;
  const height = box[3]! - box[1]! + 1;
  const lines = compression === 3 ? 16 : 1;
  if (![0, 2, 3].includes(compression)) throw new Error(`compression ${compression}`);
  const chunks = Math.ceil(height / lines);
  const channels: ExrChannels['channels'] = {};
  for (const c of list) channels[c.name] = { type: c.type, values: new Float32Array(width * height) };
  const lineBytes = list.reduce((n, c) => n + width * (c.type === 'half' ? 2 : 4), 0);
  for (let k = 0; k < chunks; k++) {
    let offset = Number(view.getBigUint64(at + 8 * k, true));
    const y0 = view.getInt32(offset, true) - box[1]!;
    const size = view.getInt32(offset + 4, true);
    offset += 8;
    const count = Math.min(lines, height - y0);
    let data = bytes.subarray(offset, offset + size);
    if (compression !== 0 && size < lineBytes * count) {
      const t = unzlibSync(data);
      for (let i = 1; i < t.length; i++) t[i] = (t[i - 1]! + t[i]! - 128) & 0xff;
      const out = new Uint8Array(t.length);
      const half = (t.length + 1) >> 1;
      for (let i = 0; i < t.length; i++) out[i] = i % 2 === 0 ? t[i >> 1]! : t[half + (i >> 1)]!;
      data = out;
    }
    const d = new DataView(data.buffer, data.byteOffset, data.byteLength);
    let p = 0;
    for (let y = y0; y < y0 + count; y++) {
      for (const c of list) {
        const target = channels[c.name]!.values;
        for (let x = 0; x < width; x++) {
          target[y * width + x] = c.type === 'half' ? halfToFloat(d.getUint16(p, true)) : d.getFloat32(p, true);
          p += c.type === 'half' ? 2 : 4;
        }
      }
    }
  }
  return { width, height, channels };
}
