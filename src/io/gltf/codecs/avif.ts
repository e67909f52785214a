/**
 * AVIF images -> RGBA8 in Node, with @jsquash/avif (libavif + dav1d compiled to WebAssembly by
 * Squoosh). Browsers decode AVIF themselves (createImageBitmap, image-decoding.ts). The decoder's
 * WebAssembly comes embedded (avif-decoder-wasm.generated.ts): its own glue would look for the
 * .wasm next to itself through import.meta.url, which Node's fetch cannot read.
 */
import type { WavefrontImageInput } from '../../../scene/types.ts';
import { compileEmbeddedWasm } from './embedded-wasm.ts';

interface JsquashAvifDecode {
  default(buffer: ArrayBuffer, options?: { bitDepth?: number }): Promise<{ width: number; height: number; data: Uint8ClampedArray }>;
  init(module: WebAssembly.Module, options?: object): unknown;
}

let decoder: Promise<JsquashAvifDecode['default']> | undefined;

/**
 * The decoder's C++ returns `new ImageData(data, width, height)` through embind; Node has no
 * ImageData, so a minimal one (the three fields it sets) is defined where none exists.
 */
function ensureImageData(): void {
  const scope = globalThis as { ImageData?: unknown };
  if (scope.ImageData !== undefined) return;
  scope.ImageData = class ImageData {
    readonly data: Uint8ClampedArray;
    readonly width: number;
    readonly height: number;
    constructor(data: Uint8ClampedArray, width: number, height: number) {
      this.data = data;
      this.width = width;
      this.height = height;
    }
  };
}

function loadDecoder(): Promise<JsquashAvifDecode['default']> {
  decoder ??= (async () => {
    // A variable specifier: Node only, bundlers leave it alone.
    const specifier = '@jsquash/avif/decode.js';
    const [avif, { avifDecoderWasm }] = await Promise.all([import(specifier) as Promise<JsquashAvifDecode>, import('./avif-decoder-wasm.generated.ts') as Promise<{ avifDecoderWasm: string }>]);
    ensureImageData();
    await avif.init(await compileEmbeddedWasm(avifDecoderWasm));
    return avif.default;
  })();
  decoder.catch(() => (decoder = undefined));
  return decoder;
}

/** Decodes AVIF bytes (8 bits per channel; deeper images are reduced by libavif). */
export async function decodeAvif(bytes: Uint8Array): Promise<WavefrontImageInput> {
  const decode = await loadDecoder();
  const exact = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength) as ArrayBuffer;
  const image = await decode(exact, { bitDepth: 8 });
  if (!(image.width > 0 && image.height > 0) || image.data.length !== image.width * image.height * 4) throw new Error('libavif returned no RGBA image');
  return { width: image.width, height: image.height, data: new Uint8Array(image.data.buffer, image.data.byteOffset, image.data.byteLength) };
}
