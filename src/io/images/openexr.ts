import { GpuRendererError } from '../../errors/gpu-renderer-error.ts';
import { defaultResourcePolicy, type DecodeBudget } from '../resource-policy.ts';
import { halfBitsToFloat32 } from '../../math/half-float.ts';
import { validateOpenExr } from './openexr-header.ts';
import { parseExrInWorker } from './openexr-worker.ts';
import type { DecodedHdrImage } from './radiance-hdr.ts';

/**
 * OpenEXR decoding through three.js's EXRLoader (`three/examples/jsm/loaders/EXRLoader.js`:
 * maintained, pure JS, runs in Node and browsers; scanline and tiled files, half / float / uint
 * channels, NONE, RLE, ZIPS, ZIP, PIZ, PXR24, B44, B44A, DWAA and DWAB compression).
 *
 * `three` is an optional peer dependency and never part of this package's static import graph: a
 * bundle of EXRLoader pulls in about 290 kB of three's core (minified; 70 kB gzipped), so it is
 * loaded only when an EXR is decoded: through a variable specifier (Node, or browsers with an import
 * map), or from the `EXRLoader` class the caller passes (bundled browser apps:
 * `import { EXRLoader } from 'three/examples/jsm/loaders/EXRLoader.js'`).
 */

/** The part of three.js's EXRLoader this package uses. */
export interface ExrLoaderLike {
  setDataType(type: number): unknown;
  parse(buffer: ArrayBuffer): { width: number; height: number; data: ArrayLike<number>; format?: number };
}
export type ExrLoaderConstructor = new () => ExrLoaderLike;

/** three.js's FloatType constant (THREE.FloatType, stable since r70). */
const THREE_FLOAT_TYPE = 1015;
/** three.js's RGBAFormat constant. */
const THREE_RGBA_FORMAT = 1023;

/** OpenEXR magic number 20000630 (little-endian 76 2f 31 01). */
export function isOpenExr(bytes: Uint8Array): boolean {
  return bytes.length >= 4 && bytes[0] === 0x76 && bytes[1] === 0x2f && bytes[2] === 0x31 && bytes[3] === 0x01;
}

async function importExrLoader(field: string): Promise<ExrLoaderConstructor> {
  const specifier = 'three/examples/jsm/loaders/EXRLoader.js';
  try {
    const module = (await import(specifier)) as { EXRLoader: ExrLoaderConstructor };
    return module.EXRLoader;
  } catch (cause) {
    throw new GpuRendererError(
      'INVALID_ENVIRONMENT',
      'decoding OpenEXR needs three.js\'s EXRLoader: install the optional peer dependency "three", or pass { EXRLoader } from three/examples/jsm/loaders/EXRLoader.js',
      { field, cause },
    );
  }
}

/** Options of `decodeOpenExr`. */
export interface DecodeOpenExrOptions {
  /** A load's resource budget, charged with the decoded texels before they are allocated. */
  budget?: DecodeBudget;
  /** Largest width or height, default the resource policy's `maxImageDimension` (16384). */
  maxImageDimension?: number;
  /** Deadline of the decoder thread (Node), ms; default 60000. */
  decodeTimeoutMs?: number;
  /** Terminates the decoder thread and rejects with the signal's reason. */
  signal?: AbortSignal;
}

/**
 * Decodes OpenEXR bytes to RGBA float32, top row first (EXR's y grows downwards). The file's
 * structure is validated first (openexr-header.ts: what EXRLoader would read, so that it cannot
 * read past the end or loop on the header), its size checked against the largest map side, and the
 * decoded texels charged to the budget before EXRLoader allocates them. In Node, without a `loader`
 * given, EXRLoader runs in a worker thread terminated at `decodeTimeoutMs` (openexr-worker.ts: its
 * Huffman decoder can loop forever on corrupt data); elsewhere it runs on the calling thread.
 */
export async function decodeOpenExr(bytes: Uint8Array, field = 'source', loader?: ExrLoaderConstructor, options: DecodeOpenExrOptions = {}): Promise<DecodedHdrImage> {
  if (!isOpenExr(bytes)) throw new GpuRendererError('INVALID_ENVIRONMENT', 'OpenEXR: missing the magic number', { field });
  const header = validateOpenExr(bytes, field, options.maxImageDimension ?? defaultResourcePolicy.maxImageDimension);
  // EXRLoader's float output and this function's flipped copy.
  options.budget?.charge(header.width * header.height * 32, { code: 'INVALID_ENVIRONMENT', field }, `the ${header.width} x ${header.height} OpenEXR texels`);
  const unreadable = (reason: string, cause?: unknown): GpuRendererError =>
    new GpuRendererError('INVALID_ENVIRONMENT', `OpenEXR: unreadable or truncated file (${reason})`, cause === undefined ? { field } : { field, cause });
  let parsed: ReturnType<ExrLoaderLike['parse']> | undefined;
  if (loader === undefined) {
    const timeout = options.decodeTimeoutMs ?? 60_000;
    // EXRLoader reads through a DataView of the whole buffer: hand it exactly these bytes.
    const result = await parseExrInWorker(bytes.slice().buffer, timeout, options.signal);
    if ('parsed' in result) parsed = result.parsed;
    else if ('timedOut' in result) {
      throw new GpuRendererError('INVALID_ENVIRONMENT', `OpenEXR: the decoder did not finish within ${timeout} ms (resourcePolicy.decodeTimeoutMs): the compressed data is corrupt`, { field });
    } else if ('error' in result) throw unreadable(result.error);
  }
  if (parsed === undefined) {
    const Loader = loader ?? (await importExrLoader(field));
    try {
      const instance = new Loader();
      instance.setDataType(THREE_FLOAT_TYPE);
      parsed = instance.parse(bytes.slice().buffer);
    } catch (cause) {
      throw unreadable(cause instanceof Error ? cause.message : String(cause), cause);
    }
  }
  const { width, height, data } = parsed;
  if (width !== header.width || height !== header.height || data.length !== width * height * 4 || (parsed.format !== undefined && parsed.format !== THREE_RGBA_FORMAT)) {
    throw new GpuRendererError('INVALID_ENVIRONMENT', `OpenEXR: decoder returned ${width} x ${height} with ${data.length} values, expected RGBA`, { field });
  }
  // EXRLoader flips rows for WebGL (its row 0 is the bottom); undo that.
  const isHalf = data instanceof Uint16Array;
  const out = new Float32Array(width * height * 4);
  for (let y = 0; y < height; y++) {
    const src = (height - 1 - y) * width * 4;
    const dst = y * width * 4;
    for (let k = 0; k < width * 4; k++) out[dst + k] = isHalf ? halfBitsToFloat32(data[src + k]!) : data[src + k]!;
  }
  return { width, height, data: out };
}
