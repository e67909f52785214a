/**
 * Reader of Open Image Denoise's Tensor Archive (TZA) weight files, version 2 (OIDN core/tza.cpp,
 * training/tza.py): a header (magic 0x41D7, major 2, minor, u64 table offset), then at the table
 * offset a u32 tensor count and per tensor: u16 name length + name, u8 rank, rank x u32 dims, the
 * layout as `rank` characters (`x` or `oihw`), the data type (`f` float32, `h` float16) and the u64
 * offset of its data. Everything little-endian. Every read is bounds-checked: a truncated or
 * hostile file is a typed error, never an out-of-range view.
 */
import { GpuRendererError } from '../../../errors/gpu-renderer-error.ts';

export interface TzaTensor {
  name: string;
  dims: number[];
  layout: 'x' | 'oihw';
  /** The values as float32 (float16 data widened exactly). */
  data: Float32Array;
}

const MAGIC = 0x41d7;

function corrupt(field: string, message: string): never {
  throw new GpuRendererError('INVALID_OPTION', `not a valid OIDN weights (TZA) file: ${message}`, { field });
}

/** IEEE 754 binary16 -> number (exact). */
export function halfToFloat(h: number): number {
  const sign = h & 0x8000 ? -1 : 1;
  const exponent = (h >> 10) & 0x1f;
  const mantissa = h & 0x3ff;
  if (exponent === 0) return sign * mantissa * 2 ** -24;
  if (exponent === 31) return mantissa ? Number.NaN : sign * Infinity;
  return sign * (1 + mantissa / 1024) * 2 ** (exponent - 15);
}

/** Parses a TZA blob into its tensors by name. `field` names the input in errors. */
export function parseTza(bytes: ArrayBuffer | ArrayBufferView, field = 'weights'): Map<string, TzaTensor> {
  const view = ArrayBuffer.isView(bytes) ? new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength) : bytes instanceof ArrayBuffer ? new DataView(bytes) : corrupt(field, 'expected an ArrayBuffer or a typed array');
  const size = view.byteLength;
  let at = 0;
  const need = (n: number, what: string): void => {
    if (!(at >= 0 && at + n <= size)) corrupt(field, `${what} at byte ${at} runs past the end (${size} bytes)`);
  };
  const u8 = (what: string): number => (need(1, what), view.getUint8(at++));
  const u16 = (what: string): number => (need(2, what), (at += 2), view.getUint16(at - 2, true));
  const u32 = (what: string): number => (need(4, what), (at += 4), view.getUint32(at - 4, true));
  const u64 = (what: string): number => {
    need(8, what);
    const value = view.getBigUint64(at, true);
    at += 8;
    if (value > BigInt(size)) corrupt(field, `${what} ${value} lies past the end (${size} bytes)`);
    return Number(value);
  };
  if (u16('magic') !== MAGIC) corrupt(field, 'bad magic number');
  const major = u8('version');
  u8('version');
  if (major !== 2) corrupt(field, `unsupported version ${major} (expected 2)`);
  at = u64('table offset');
  const count = u32('tensor count');
  const tensors = new Map<string, TzaTensor>();
  const decoder = new TextDecoder();
  for (let i = 0; i < count; i++) {
    const nameLength = u16('name length');
    need(nameLength, 'name');
    const name = decoder.decode(new Uint8Array(view.buffer, view.byteOffset + at, nameLength));
    at += nameLength;
    const rank = u8('rank');
    const dims: number[] = [];
    for (let d = 0; d < rank; d++) dims.push(u32('dimension'));
    need(rank, 'layout');
    const layout = decoder.decode(new Uint8Array(view.buffer, view.byteOffset + at, rank));
    at += rank;
    if (layout !== 'x' && layout !== 'oihw') corrupt(field, `tensor ${name}: unknown layout ${JSON.stringify(layout)}`);
    const type = String.fromCharCode(u8('data type'));
    if (type !== 'f' && type !== 'h') corrupt(field, `tensor ${name}: unsupported data type ${JSON.stringify(type)}`);
    const offset = u64('data offset');
    const elements = dims.reduce((a, b) => a * b, 1);
    const bytesPer = type === 'f' ? 4 : 2;
    if (!(offset + elements * bytesPer <= size)) corrupt(field, `tensor ${name}: data runs past the end`);
    const data = new Float32Array(elements);
    for (let e = 0; e < elements; e++) data[e] = type === 'f' ? view.getFloat32(offset + 4 * e, true) : halfToFloat(view.getUint16(offset + 2 * e, true));
    if (tensors.has(name)) corrupt(field, `tensor ${name} appears twice`);
    tensors.set(name, { name, dims, layout, data });
  }
  return tensors;
}
