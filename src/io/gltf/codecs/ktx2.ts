/**
 * KTX 2.0 images -> RGBA8, top row first: the textures of KHR_texture_basisu, and KTX2 files some
 * tools write as plain image sources. The container is read with ktx-parse; every mip level of a 2D
 * texture (one face, one layer) is decoded, level 0 as the image and the rest as its `mipLevels`
 * (used as the texture's mip chain, as the file's author filtered it):
 * - Basis Universal payloads (vkFormat UNDEFINED: ETC1S / BasisLZ or UASTC, Zstandard or not) are
 *   transcoded to RGBA32 by Binomial's transcoder (basis-transcoder.generated.ts), compiled on
 *   first use;
 * - uncompressed 8-bit formats (R8, R8G8, R8G8B8, B8G8R8, R8G8B8A8, B8G8R8A8; UNORM or SRGB) are
 *   copied, after Zstandard (fzstd) or zlib (fflate) supercompression; missing channels read as
 *   Vulkan samples them (G = B = 0, A = 1).
 * Everything else (HDR and block-compressed formats, arrays, cube maps) is refused with an error.
 * Which slot the image feeds decides sRGB or linear decoding, as for PNG; KTX2's transfer function
 * is not consulted.
 */
import { read, type KTX2Container } from 'ktx-parse';
import type { WavefrontImageInput, WavefrontImageLevel } from '../../../scene/types.ts';
import { compileEmbeddedWasm, instantiateWith } from './embedded-wasm.ts';

/** KTX2 supercompression schemes (KTX 2.0 section 3.12). */
const SUPERCOMPRESSION = { none: 0, basisLZ: 1, zstd: 2, zlib: 3 } as const;

/** Uncompressed 8-bit vkFormats: [channels, order] with order mapping stored bytes to R, G, B, A. */
const PLAIN_FORMATS: Readonly<Record<number, { name: string; channels: number; order: readonly number[] }>> = {
  9: { name: 'R8_UNORM', channels: 1, order: [0] },
  15: { name: 'R8_SRGB', channels: 1, order: [0] },
  16: { name: 'R8G8_UNORM', channels: 2, order: [0, 1] },
  22: { name: 'R8G8_SRGB', channels: 2, order: [0, 1] },
  23: { name: 'R8G8B8_UNORM', channels: 3, order: [0, 1, 2] },
  29: { name: 'R8G8B8_SRGB', channels: 3, order: [0, 1, 2] },
  30: { name: 'B8G8R8_UNORM', channels: 3, order: [2, 1, 0] },
  36: { name: 'B8G8R8_SRGB', channels: 3, order: [2, 1, 0] },
  37: { name: 'R8G8B8A8_UNORM', channels: 4, order: [0, 1, 2, 3] },
  43: { name: 'R8G8B8A8_SRGB', channels: 4, order: [0, 1, 2, 3] },
  44: { name: 'B8G8R8A8_UNORM', channels: 4, order: [2, 1, 0, 3] },
  50: { name: 'B8G8R8A8_SRGB', channels: 4, order: [2, 1, 0, 3] },
};

/** basis_transcoder's transcoder_texture_format.cTFRGBA32. */
const TRANSCODE_RGBA32 = 13;

interface BasisKtx2File {
  isValid(): boolean;
  isHDR(): boolean;
  getWidth(): number;
  getHeight(): number;
  getLevels(): number;
  startTranscoding(): boolean;
  getImageTranscodedSizeInBytes(level: number, layer: number, face: number, format: number): number;
  transcodeImage(dst: Uint8Array, level: number, layer: number, face: number, format: number, getAlphaForOpaqueFormats: number, channel0: number, channel1: number): number;
  close(): void;
  delete(): void;
}

interface BasisModule {
  initializeBasis(): void;
  KTX2File: new (data: Uint8Array) => BasisKtx2File;
}

let basisModule: Promise<BasisModule> | undefined;

/** Binomial's transcoder, compiled once per process (or page). */
function loadBasis(): Promise<BasisModule> {
  basisModule ??= (async () => {
    const { basisTranscoderWasm, createBasisModule } = (await import('./basis-transcoder.generated.ts')) as {
      basisTranscoderWasm: string;
      createBasisModule: (moduleArg: object) => Promise<BasisModule>;
    };
    const module = await createBasisModule({ instantiateWasm: instantiateWith(await compileEmbeddedWasm(basisTranscoderWasm)) });
    module.initializeBasis();
    return module;
  })();
  basisModule.catch(() => (basisModule = undefined));
  return basisModule;
}

/** Whether the rows are stored bottom first (KTXorientation "ru"); glTF's default is "rd". */
function bottomUp(container: KTX2Container): boolean {
  const orientation = container.keyValue.KTXorientation;
  const text = typeof orientation === 'string' ? orientation : orientation instanceof Uint8Array ? new TextDecoder().decode(orientation) : '';
  return text.replace(/\0+$/, '')[1] === 'u';
}

function flipRows(image: WavefrontImageLevel): WavefrontImageLevel {
  const row = image.width * 4;
  const out = new Uint8Array(image.data.length);
  for (let y = 0; y < image.height; y++) out.set(image.data.subarray((image.height - 1 - y) * row, (image.height - y) * row), y * row);
  return { ...image, data: out };
}

/** Size of mip level k (KTX 2.0 section 4.1: max(1, floor(size / 2^k))). */
function levelSize(container: KTX2Container, k: number): [number, number] {
  return [Math.max(1, container.pixelWidth >> k), Math.max(1, container.pixelHeight >> k)];
}

async function inflateLevel(container: KTX2Container, k: number): Promise<Uint8Array> {
  const level = container.levels[k]!;
  switch (container.supercompressionScheme) {
    case SUPERCOMPRESSION.none:
      return level.levelData;
    case SUPERCOMPRESSION.zstd: {
      const { decompress } = await import('fzstd');
      return decompress(level.levelData, new Uint8Array(level.uncompressedByteLength));
    }
    case SUPERCOMPRESSION.zlib: {
      const { unzlibSync } = await import('fflate');
      return unzlibSync(level.levelData, { out: new Uint8Array(level.uncompressedByteLength) });
    }
    default:
      throw new Error(`supercompression scheme ${container.supercompressionScheme} does not apply to vkFormat ${container.vkFormat}`);
  }
}

async function decodePlain(container: KTX2Container, format: { name: string; channels: number; order: readonly number[] }, k: number): Promise<WavefrontImageLevel> {
  const [width, height] = levelSize(container, k);
  const data = await inflateLevel(container, k);
  // KTX 2.0 rows of uncompressed formats are tightly packed (section 3.10.1).
  if (data.length < width * height * format.channels) throw new Error(`level ${k} holds ${data.length} bytes, ${format.name} at ${width} x ${height} needs ${width * height * format.channels}`);
  const out = new Uint8Array(width * height * 4);
  for (let p = 0; p < width * height; p++) {
    const s = p * format.channels;
    out[p * 4 + 3] = 255;
    for (let c = 0; c < format.channels; c++) out[p * 4 + format.order[c]!] = data[s + c]!;
  }
  return { width, height, data: out };
}

async function transcodeBasis(bytes: Uint8Array, container: KTX2Container): Promise<WavefrontImageLevel[]> {
  const basis = await loadBasis();
  const file = new basis.KTX2File(bytes);
  try {
    if (!file.isValid()) throw new Error('the Basis transcoder rejects the file');
    if (file.isHDR()) throw new Error('HDR (UASTC HDR) textures are not supported');
    if (!file.startTranscoding()) throw new Error('the Basis transcoder cannot start');
    if (file.getWidth() !== container.pixelWidth || file.getHeight() !== container.pixelHeight || file.getLevels() !== container.levels.length) {
      throw new Error(`the Basis transcoder reads ${file.getWidth()} x ${file.getHeight()} with ${file.getLevels()} levels, the container says ${container.pixelWidth} x ${container.pixelHeight} with ${container.levels.length}`);
    }
    return container.levels.map((_, k) => {
      const [width, height] = levelSize(container, k);
      const data = new Uint8Array(file.getImageTranscodedSizeInBytes(k, 0, 0, TRANSCODE_RGBA32));
      if (data.length !== width * height * 4 || !file.transcodeImage(data, k, 0, 0, TRANSCODE_RGBA32, 0, -1, -1)) throw new Error(`the Basis transcoder failed on level ${k}`);
      return { width, height, data };
    });
  } finally {
    file.close();
    file.delete();
  }
}

/** Decodes KTX2 bytes (see the module comment); errors say why in their message. */
export async function decodeKtx2(bytes: Uint8Array): Promise<WavefrontImageInput> {
  let container: KTX2Container;
  try {
    container = read(bytes);
  } catch (error) {
    throw new Error(`the KTX2 container does not parse (${(error as Error).message})`, { cause: error });
  }
  const { pixelWidth, pixelHeight, pixelDepth, layerCount, faceCount, vkFormat } = container;
  if (pixelWidth === 0 || pixelHeight === 0 || pixelDepth > 1 || layerCount > 1 || faceCount !== 1) {
    throw new Error(`only 2D textures are supported (got ${pixelWidth} x ${pixelHeight} x ${pixelDepth}, ${layerCount} layers, ${faceCount} faces)`);
  }
  if (container.levels.length === 0) throw new Error('the file holds no mip level');
  // levelCount 0 in the header means "generate the chain" (section 3.7): the file still stores level 0 only.
  if (container.levels.length > 32 - Math.clz32(Math.max(pixelWidth, pixelHeight))) throw new Error(`${container.levels.length} mip levels exceed the chain of a ${pixelWidth} x ${pixelHeight} texture`);
  let levels: WavefrontImageLevel[];
  if (vkFormat === 0) levels = await transcodeBasis(bytes, container);
  else {
    const format = PLAIN_FORMATS[vkFormat];
    if (format === undefined) throw new Error(`vkFormat ${vkFormat} is not supported (Basis Universal, or uncompressed 8-bit R / RG / RGB / BGR / RGBA / BGRA)`);
    levels = [];
    for (let k = 0; k < container.levels.length; k++) levels.push(await decodePlain(container, format, k));
  }
  if (bottomUp(container)) levels = levels.map(flipRows);
  const [image, ...mipLevels] = levels as [WavefrontImageLevel, ...WavefrontImageLevel[]];
  return mipLevels.length > 0 ? { ...image, mipLevels } : image;
}
