/**
 * Structural validation of an OpenEXR file before three.js's EXRLoader decodes it ("OpenEXR File
 * Layout", openexr.com: magic and version, header attributes, offset table, chunks). EXRLoader
 * trusts its input: a NUL-terminated string running off the end of the buffer loops forever (a
 * truncated 10-byte file hangs it), attribute values are read at their type's size whatever size
 * the file declares, and scanline chunks are read one after another from the end of the offset
 * table. So everything it will read is checked here first, as it will read it: every attribute
 * inside the file with the size of its type, the channel list, the data window against the largest
 * map side, the compression, the offset table's extent, and each chunk's position, size and
 * scanline or tile coordinates.
 *
 * Read as environment maps: single-part scanline files and single-part ONE_LEVEL tiled files with
 * half or float channels sampled at every texel (what HDRI maps are). Multi-part, deep, mip- or
 * rip-mapped tiled files, UINT and subsampled channels are refused with a typed error.
 */
import { GpuRendererError } from '../../errors/gpu-renderer-error.ts';

export interface ExrHeaderSummary {
  width: number;
  height: number;
  compression: string;
  tiled: boolean;
}

/** Scanlines per chunk of each compression (OpenEXR "Compression" table), by code. */
const COMPRESSIONS: ReadonlyArray<{ name: string; lines: number }> = [
  { name: 'NONE', lines: 1 },
  { name: 'RLE', lines: 1 },
  { name: 'ZIPS', lines: 1 },
  { name: 'ZIP', lines: 16 },
  { name: 'PIZ', lines: 32 },
  { name: 'PXR24', lines: 16 },
  { name: 'B44', lines: 32 },
  { name: 'B44A', lines: 32 },
  { name: 'DWAA', lines: 32 },
  { name: 'DWAB', lines: 256 },
];

/** Bytes EXRLoader reads for attribute types it parses at a fixed size. */
const FIXED_SIZES: Readonly<Record<string, number>> = {
  chromaticities: 32,
  compression: 1,
  box2i: 16,
  envmap: 1,
  tiledesc: 9,
  lineOrder: 1,
  float: 4,
  v2f: 8,
  v3f: 12,
  int: 4,
  rational: 8,
  timecode: 8,
};

/**
 * Checks `bytes` as described above; returns the image size. Errors: INVALID_ENVIRONMENT at
 * `field`, the message saying what and where (byte offsets).
 */
export function validateOpenExr(bytes: Uint8Array, field: string, maxDimension: number): ExrHeaderSummary {
  function fail(message: string): never {
    throw new GpuRendererError('INVALID_ENVIRONMENT', `OpenEXR: ${message}`, { field });
  }
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const n = bytes.length;
  if (n < 8 || view.getUint32(0, true) !== 20000630) fail('missing the magic number 20000630');
  const version = bytes[4]!;
  const flags = view.getUint32(4, true) >>> 8;
  if (version !== 2) fail(`version ${version} (expected 2)`);
  const tiled = (flags & 0x02) !== 0;
  const longNames = (flags & 0x04) !== 0;
  if (flags & 0x08) fail('deep (non-image) data is not an environment map');
  if (flags & 0x10) fail('multi-part files are not read; save the map as a single-part file');
  if (flags & ~0x06) fail(`unknown version flags 0x${(flags << 8).toString(16)}`);

  let pos = 8;
  const string = (what: string, maxLength: number): string => {
    const end = bytes.indexOf(0, pos);
    if (end < 0 || end - pos > maxLength) fail(`${what} at byte ${pos} is not a NUL-terminated string of at most ${maxLength} bytes inside the file`);
    const text = String.fromCharCode(...bytes.subarray(pos, end));
    pos = end + 1;
    return text;
  };
  const nameLimit = longNames ? 255 : 31;
  const attributes = new Map<string, { type: string; start: number; size: number }>();
  for (;;) {
    if (pos >= n) fail('the header has no terminating NUL byte');
    const name = string('an attribute name', nameLimit);
    if (name === '') break;
    const type = string(`the type of attribute "${name}"`, nameLimit);
    if (pos + 4 > n) fail(`attribute "${name}" has no size`);
    const size = view.getInt32(pos, true);
    pos += 4;
    if (size < 0 || pos + size > n) fail(`attribute "${name}" declares ${size} bytes at byte ${pos}, past the end of the file (${n} bytes)`);
    const fixed = FIXED_SIZES[type];
    if (fixed !== undefined && size !== fixed) fail(`attribute "${name}" of type ${type} declares ${size} bytes (a ${type} has ${fixed})`);
    if (attributes.has(name)) fail(`attribute "${name}" appears twice`);
    attributes.set(name, { type, start: pos, size });
    pos += size;
  }
  const headerEnd = pos;
  const attribute = (name: string, type: string): { start: number; size: number } => {
    const a = attributes.get(name);
    if (a === undefined) fail(`the header lacks the required attribute "${name}"`);
    if (a.type !== type) fail(`attribute "${name}" has type ${a.type} (expected ${type})`);
    return a;
  };

  // Channel list: entries of name, pixel type, pLinear, 3 reserved bytes, x and y sampling; a NUL ends it.
  const chlist = attribute('channels', 'chlist');
  const chEnd = chlist.start + chlist.size - 1;
  if (chlist.size < 1 || bytes[chEnd] !== 0) fail('the channel list does not end with a NUL byte');
  pos = chlist.start;
  let channels = 0;
  while (pos < chEnd) {
    const name = string('a channel name', nameLimit);
    if (name === '' || pos + 16 > chEnd) fail(`channel entry ${channels} at byte ${pos} is malformed`);
    const pixelType = view.getInt32(pos, true);
    const xSampling = view.getInt32(pos + 8, true);
    const ySampling = view.getInt32(pos + 12, true);
    if (pixelType !== 1 && pixelType !== 2) fail(`channel "${name}" has pixel type ${pixelType} (only HALF = 1 and FLOAT = 2 are radiance)`);
    if (xSampling !== 1 || ySampling !== 1) fail(`channel "${name}" is subsampled ${xSampling} x ${ySampling}; every channel must be sampled at every texel`);
    pos += 16;
    channels++;
  }
  if (pos !== chEnd) fail('the channel list overruns its declared size');
  if (channels === 0) fail('the channel list is empty');

  const compressionCode = bytes[attribute('compression', 'compression').start]!;
  const compression = COMPRESSIONS[compressionCode];
  if (compression === undefined) fail(`unknown compression ${compressionCode}`);

  const dw = attribute('dataWindow', 'box2i').start;
  const xMin = view.getInt32(dw, true);
  const yMin = view.getInt32(dw + 4, true);
  const xMax = view.getInt32(dw + 8, true);
  const yMax = view.getInt32(dw + 12, true);
  const width = xMax - xMin + 1;
  const height = yMax - yMin + 1;
  if (!(width >= 1 && height >= 1)) fail(`empty data window (${xMin}, ${yMin})..(${xMax}, ${yMax})`);
  if (width > maxDimension || height > maxDimension) fail(`the data window is ${width} x ${height} texels, over the largest side of ${maxDimension}`);
  const lineOrder = attributes.get('lineOrder');
  if (lineOrder !== undefined && (lineOrder.type !== 'lineOrder' || bytes[lineOrder.start]! > 2)) fail('lineOrder is not INCREASING_Y, DECREASING_Y or RANDOM_Y');

  const int32 = (at: number, what: string): number => {
    if (at + 4 > n) fail(`${what} at byte ${at} is past the end of the file`);
    return view.getInt32(at, true);
  };
  const chunk = (at: number, header: number, what: string): number => {
    const size = int32(at + header - 4, `the size of ${what}`);
    if (size < 0 || at + header + size > n) fail(`${what} at byte ${at} declares ${size} bytes, past the end of the file (${n} bytes)`);
    return at + header + size;
  };

  if (tiled) {
    const t = attribute('tiles', 'tiledesc').start;
    const xSize = view.getUint32(t, true);
    const ySize = view.getUint32(t + 4, true);
    const mode = bytes[t + 8]!;
    if ((mode & 0x0f) !== 0) fail(`tiles with level mode ${mode & 0x0f} (mip- or rip-mapped) are not read; only ONE_LEVEL`);
    if (mode >> 4 > 1) fail(`unknown tile rounding mode ${mode >> 4}`);
    if (xSize < 1 || ySize < 1 || xSize > maxDimension || ySize > maxDimension) fail(`tile size ${xSize} x ${ySize} is out of range`);
    const tilesX = Math.ceil(width / xSize);
    const tilesY = Math.ceil(height / ySize);
    // The offset table (one 64-bit offset per tile), then tiles: x, y, level x, level y, size, data.
    pos = headerEnd + 8 * tilesX * tilesY;
    if (pos > n) fail(`the offset table of ${tilesX * tilesY} tiles runs past the end of the file`);
    for (let k = 0; k < tilesX * tilesY; k++) {
      const tx = int32(pos, `tile ${k}`);
      const ty = int32(pos + 4, `tile ${k}`);
      if (tx < 0 || tx >= tilesX || ty < 0 || ty >= tilesY) fail(`tile ${k} at byte ${pos} claims tile (${tx}, ${ty}) of ${tilesX} x ${tilesY}`);
      pos = chunk(pos, 20, `tile ${k}`);
    }
  } else {
    const chunks = Math.ceil(height / compression.lines);
    pos = headerEnd + 8 * chunks;
    if (pos > n) fail(`the offset table of ${chunks} chunks runs past the end of the file`);
    for (let k = 0; k < chunks; k++) {
      const y = int32(pos, `chunk ${k}`);
      if (y < yMin || y > yMax || (y - yMin) % compression.lines !== 0) fail(`chunk ${k} at byte ${pos} starts at scanline ${y}, not a ${compression.lines}-line block of ${yMin}..${yMax}`);
      pos = chunk(pos, 8, `chunk ${k}`);
    }
  }
  return { width, height, compression: compression.name, tiled };
}
