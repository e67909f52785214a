/**
 * OpenEXR writer: single-part scanline files ("OpenEXR File Layout", openexr.com), HALF or FLOAT
 * channels, NO / ZIPS / ZIP compression, AOVs as extra layers named `<layer>.<channel>`.
 * Pure TypeScript plus fflate's zlib, so it runs in browsers and Node.js alike.
 */
import { zlibSync } from 'fflate';
import { GpuRendererError } from '../../errors/gpu-renderer-error.ts';
import { wavefrontAovChannels, wavefrontIntegerAovs, isWavefrontAovName, type WavefrontAovName } from '../../film/aovs.ts';
import { ByteWriter } from './byte-writer.ts';
import { float32ToHalfBits } from '../../math/half-float.ts';
import { requireLinearRgbaImage, type LinearRgbaImage } from './linear-image.ts';

/** `none`: raw; `zips`: zlib per scanline; `zip`: zlib per block of 16 scanlines (OpenEXR's ZIP). */
export type ExrCompression = 'none' | 'zips' | 'zip';
/** `half`: IEEE binary16 (max 65504, larger values become +Inf); `float`: IEEE binary32. */
export type ExrPixelType = 'half' | 'float';

/** A custom layer: channel `c` of `name` is written as `name.c`, read from `data` interleaved. */
export interface ExrLayer {
  name: string;
  /** Channel suffixes, in the order they are interleaved in `data` (e.g. ['R', 'G', 'B']). */
  channels: readonly string[];
  /** width * height * k floats with k >= channels.length; the first channels.length are written. */
  data: Float32Array;
  pixelType?: ExrPixelType;
}

export interface EncodeExrOptions {
  /** Default 'zip' (lossless). */
  compression?: ExrCompression;
  /** Pixel type of the beauty and AOV channels; default 'float' (no overflow, exact radiance). */
  pixelType?: ExrPixelType;
  /** Write the beauty's alpha (coverage) as channel A; default true. */
  alpha?: boolean;
  /**
   * Renderer AOVs, each width * height * k floats with k >= the AOV's channel count (so RGBA or
   * vec4 buffers can be passed as they are): albedo -> albedo.R/G/B, normal -> normal.X/Y/Z,
   * depth -> depth.Z, objectId / materialId -> <name>.id, variance -> variance.R/G/B,
   * sampleCount -> sampleCount.count (ids and counts always FLOAT).
   */
  aovs?: Partial<Record<WavefrontAovName, Float32Array>>;
  /** Further layers with caller-chosen names. */
  layers?: readonly ExrLayer[];
}

interface ChannelSource {
  name: string;
  pixelType: ExrPixelType;
  data: Float32Array;
  stride: number;
  component: number;
}

const magic = 20000630;
const compressionIds: Record<ExrCompression, number> = { none: 0, zips: 2, zip: 3 };
const linesPerChunk: Record<ExrCompression, number> = { none: 1, zips: 1, zip: 16 };
const pixelTypeIds: Record<ExrPixelType, number> = { half: 1, float: 2 };
const bytesPerSample: Record<ExrPixelType, number> = { half: 2, float: 4 };

function fail(field: string, message: string): never {
  throw new GpuRendererError('INVALID_OPTION', message, { field });
}

function requirePixelType(value: unknown, field: string): ExrPixelType {
  if (value !== 'half' && value !== 'float') fail(field, `expected 'half' or 'float', got ${JSON.stringify(value)}`);
  return value;
}

/** Printable ASCII without NUL, at most 255 bytes (the long-name limit of the file format). */
function requireChannelName(name: string, field: string): void {
  if (typeof name !== 'string' || name.length === 0 || name.length > 255 || !/^[\x20-\x7e]+$/.test(name)) {
    fail(field, `expected 1 to 255 printable ASCII characters, got ${JSON.stringify(name)}`);
  }
}

function layerSources(name: string, channels: readonly string[], data: unknown, pixelType: ExrPixelType, pixels: number, field: string): ChannelSource[] {
  if (!(data instanceof Float32Array) || data.length === 0 || data.length % pixels !== 0 || data.length / pixels < channels.length) {
    fail(field, `expected a Float32Array of width * height * k floats with k >= ${channels.length}`);
  }
  const stride = data.length / pixels;
  return channels.map((suffix, component) => ({ name: `${name}.${suffix}`, pixelType, data, stride, component }));
}

function collectChannels(image: LinearRgbaImage, options: EncodeExrOptions, pixels: number): ChannelSource[] {
  const pixelType = requirePixelType(options.pixelType ?? 'float', 'pixelType');
  const beauty = options.alpha === false ? ['R', 'G', 'B'] : ['R', 'G', 'B', 'A'];
  const sources: ChannelSource[] = beauty.map((name) => ({ name, pixelType, data: image.data, stride: 4, component: 'RGBA'.indexOf(name) }));
  for (const [aov, data] of Object.entries(options.aovs ?? {})) {
    if (data === undefined) continue;
    if (!isWavefrontAovName(aov)) fail(`aovs.${aov}`, `unknown AOV (expected one of ${Object.keys(wavefrontAovChannels).join(', ')})`);
    // Ids and counts stay exact: half floats hold integers only up to 2048.
    const type = wavefrontIntegerAovs.includes(aov) ? 'float' : pixelType;
    sources.push(...layerSources(aov, wavefrontAovChannels[aov], data, type, pixels, `aovs.${aov}`));
  }
  (options.layers ?? []).forEach((layer, i) => {
    const field = `layers[${i}]`;
    requireChannelName(layer?.name, `${field}.name`);
    if (!Array.isArray(layer.channels) || layer.channels.length === 0) fail(`${field}.channels`, 'expected a non-empty array of channel names');
    layer.channels.forEach((c, k) => requireChannelName(c, `${field}.channels[${k}]`));
    const type = requirePixelType(layer.pixelType ?? pixelType, `${field}.pixelType`);
    sources.push(...layerSources(layer.name, layer.channels, layer.data, type, pixels, `${field}.data`));
  });
  sources.forEach((s) => requireChannelName(s.name, 'channels'));
  // The file stores channels sorted by name (OpenEXR's ChannelList is an ordered map; readers
  // compute each channel's position in a scanline from that order). Names are ASCII, so UTF-16
  // code unit order is byte order.
  sources.sort((a, b) => (a.name < b.name ? -1 : a.name > b.name ? 1 : 0));
  for (let i = 1; i < sources.length; i++) {
    if (sources[i].name === sources[i - 1].name) fail('layers', `channel ${JSON.stringify(sources[i].name)} is written twice`);
  }
  return sources;
}

function writeAttribute(out: ByteWriter, name: string, type: string, size: number, body: () => void): void {
  out.cString(name);
  out.cString(type);
  out.i32(size);
  const start = out.length;
  body();
  if (out.length - start !== size) throw new Error(`EXR attribute ${name}: wrote ${out.length - start} bytes, declared ${size}`);
}

function writeHeader(out: ByteWriter, channels: readonly ChannelSource[], width: number, height: number, compression: ExrCompression): void {
  const longNames = channels.some((c) => c.name.length > 31);
  out.i32(magic);
  // Version 2; bit 10 (0x400) marks names longer than 31 bytes. Single-part scanline: no other flags.
  out.i32(2 | (longNames ? 0x400 : 0));
  const chlistSize = channels.reduce((n, c) => n + c.name.length + 1 + 16, 0) + 1;
  writeAttribute(out, 'channels', 'chlist', chlistSize, () => {
    for (const c of channels) {
      out.cString(c.name);
      out.i32(pixelTypeIds[c.pixelType]);
      out.u8(0); // pLinear
      out.u8(0); // reserved
      out.u8(0);
      out.u8(0);
      out.i32(1); // xSampling
      out.i32(1); // ySampling
    }
    out.u8(0);
  });
  writeAttribute(out, 'compression', 'compression', 1, () => out.u8(compressionIds[compression]));
  const box = () => {
    out.i32(0);
    out.i32(0);
    out.i32(width - 1);
    out.i32(height - 1);
  };
  writeAttribute(out, 'dataWindow', 'box2i', 16, box);
  writeAttribute(out, 'displayWindow', 'box2i', 16, box);
  writeAttribute(out, 'lineOrder', 'lineOrder', 1, () => out.u8(0)); // INCREASING_Y: top row first
  writeAttribute(out, 'pixelAspectRatio', 'float', 4, () => out.f32(1));
  writeAttribute(out, 'screenWindowCenter', 'v2f', 8, () => {
    out.f32(0);
    out.f32(0);
  });
  writeAttribute(out, 'screenWindowWidth', 'float', 4, () => out.f32(1));
  out.u8(0); // end of header
}

/** Uncompressed chunk payload: for each scanline, each channel's row of samples in turn. */
function rawBlock(channels: readonly ChannelSource[], width: number, y0: number, lines: number): Uint8Array {
  const lineBytes = channels.reduce((n, c) => n + width * bytesPerSample[c.pixelType], 0);
  const bytes = new Uint8Array(lineBytes * lines);
  const view = new DataView(bytes.buffer);
  let offset = 0;
  for (let y = y0; y < y0 + lines; y++) {
    for (const c of channels) {
      let index = y * width * c.stride + c.component;
      if (c.pixelType === 'half') {
        for (let x = 0; x < width; x++, index += c.stride, offset += 2) view.setUint16(offset, float32ToHalfBits(c.data[index]), true);
      } else {
        for (let x = 0; x < width; x++, index += c.stride, offset += 4) view.setFloat32(offset, c.data[index], true);
      }
    }
  }
  return bytes;
}

/**
 * OpenEXR's ZIP preprocessing (ImfZip.cpp): split the bytes into even and odd positions, then
 * replace each byte by its difference to the previous one (+128), which makes float data far more
 * compressible; then zlib (RFC 1950). A chunk whose compressed form is not smaller is stored raw,
 * which readers detect from its size.
 */
function zipBlock(raw: Uint8Array): Uint8Array {
  const n = raw.length;
  const reordered = new Uint8Array(n);
  const half = (n + 1) >> 1;
  for (let i = 0, a = 0, b = half; i < n; i += 2) {
    reordered[a++] = raw[i];
    if (i + 1 < n) reordered[b++] = raw[i + 1];
  }
  for (let i = n - 1; i > 0; i--) reordered[i] = (reordered[i] - reordered[i - 1] + 128) & 0xff;
  const compressed = zlibSync(reordered);
  return compressed.length < n ? compressed : raw;
}

/**
 * Encodes linear RGBA radiance (plus optional AOVs and layers) as an OpenEXR file. The beauty is
 * channels R, G, B (and A), the layers `<name>.<channel>`; data window = display window =
 * (0, 0)-(width - 1, height - 1), increasing Y (top row first), square pixels.
 */
export function encodeExr(image: LinearRgbaImage, options: EncodeExrOptions = {}): Uint8Array {
  const pixels = requireLinearRgbaImage(image);
  const compression = options.compression ?? 'zip';
  if (!(compression in compressionIds)) fail('compression', `expected 'none', 'zips' or 'zip', got ${JSON.stringify(compression)}`);
  const channels = collectChannels(image, options, pixels);
  const { width, height } = image;
  const header = new ByteWriter();
  writeHeader(header, channels, width, height, compression);
  const blockLines = linesPerChunk[compression];
  const chunkCount = Math.ceil(height / blockLines);
  const chunks: Uint8Array[] = [];
  for (let c = 0; c < chunkCount; c++) {
    const y0 = c * blockLines;
    const raw = rawBlock(channels, width, y0, Math.min(blockLines, height - y0));
    chunks.push(compression === 'none' ? raw : zipBlock(raw));
  }
  // Offset table (absolute file offsets of each chunk), then chunks: y, byte count, data.
  const tableEnd = header.length + 8 * chunkCount;
  const total = tableEnd + chunks.reduce((n, chunk) => n + 8 + chunk.length, 0);
  const out = new Uint8Array(total);
  out.set(header.toBytes(), 0);
  const view = new DataView(out.buffer);
  let offset = tableEnd;
  chunks.forEach((chunk, c) => {
    view.setBigUint64(header.length + 8 * c, BigInt(offset), true);
    view.setInt32(offset, c * blockLines, true);
    view.setInt32(offset + 4, chunk.length, true);
    out.set(chunk, offset + 8);
    offset += 8 + chunk.length;
  });
  return out;
}
