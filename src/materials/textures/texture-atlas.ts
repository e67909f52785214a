/**
 * The material texture atlas: every texture the materials use, with its mip chain, packed into the
 * square layers of one rgba8unorm texture array, plus one TextureInfo record (block origin, size,
 * layer, mip count, sampler bits) per used (texture, sRGB-ness) pair in the materials heap, which
 * texture-sampling.wesl reads.
 *
 * A block is one image's mip chain in one encoding: sRGB use averages its levels in linear light,
 * linear use as stored, so an image used both ways gets two blocks when mipmapped. Several
 * textures naming the same image (with different samplers) share its blocks. A texture whose
 * sampler never reads mip levels needs only level 0, which any block of the same image at the same
 * size holds unchanged.
 */
import { GpuRendererError } from '../../errors/gpu-renderer-error.ts';
import { describe, fail } from '../../errors/validate.ts';
import { textureInfoLayout } from '../../gpu-layout/records.ts';
import type { Vec4Heap } from '../../gpu-layout/vec4-heap.ts';
import type { WavefrontImageInput, WavefrontTextureInput } from '../../scene/types.ts';
import { fullMipCount, mipChainLayout } from './atlas-layout.ts';
import { fitTextureToLimit, packAtlas, type AtlasLimits } from './atlas-packer.ts';
import { downscaleImage, imageMipChain, type Rgba8Image, type TexelEncoding } from './mip-chain.ts';
import { samplerBits, samplerUsesMipmaps } from './sampler-state.ts';
import { validateTextures } from './texture-input.ts';

/** A material's need for a texture: which one, and whether its RGB is sRGB-encoded colour. */
export interface TextureUsage {
  readonly texture: number;
  readonly srgb: boolean;
}

export interface TextureAtlas {
  /** Side of every layer in texels (1 when the atlas is empty). */
  readonly layerSize: number;
  /** RGBA8 texels of each layer, layerSize x layerSize, row-major. */
  readonly layers: readonly Uint8Array[];
  /** Materials-heap offset (vec4 units) of the TextureInfo of a used (texture, srgb) pair. */
  infoOffset(texture: number, srgb: boolean): number;
  /** GPU memory of the atlas texture in bytes. */
  readonly bytes: number;
  /** Distinct scene textures the atlas serves. */
  readonly textureCount: number;
  /** Blocks (mip chains) packed. */
  readonly blockCount: number;
  /** What was changed to fit the device (downscaled textures); also pushed to the caller's list. */
  readonly warnings: readonly string[];
}

interface Block {
  readonly imageKey: object;
  readonly source: Rgba8Image;
  /** Level-0 size in the atlas (smaller than the source when downscaled to fit). */
  readonly width: number;
  readonly height: number;
  readonly levels: number;
  /** 'raw': level 0 only, stored as given, valid for either encoding. */
  readonly encoding: TexelEncoding | 'raw';
  readonly textures: Set<number>;
}

function validateUsages(usages: readonly TextureUsage[], textureCount: number): TextureUsage[] {
  if (!Array.isArray(usages)) throw new TypeError(`texture usages must be an array, got ${describe(usages)}`);
  const seen = new Set<string>();
  const unique: TextureUsage[] = [];
  for (const u of usages) {
    if (!Number.isInteger(u.texture) || u.texture < 0 || u.texture >= textureCount) {
      fail('INVALID_TEXTURE', 'textures', `a material uses texture ${describe(u.texture)}, but textures has ${textureCount} entries`);
    }
    const key = `${u.texture}|${u.srgb === true}`;
    if (seen.has(key)) continue;
    seen.add(key);
    unique.push({ texture: u.texture, srgb: u.srgb === true });
  }
  return unique;
}

function validateLimits(limits: AtlasLimits): void {
  for (const name of ['maxTextureDimension2D', 'maxTextureArrayLayers'] as const) {
    const v = limits[name];
    if (!Number.isInteger(v) || v < 1) throw new RangeError(`atlas limit ${name} must be an integer >= 1, got ${describe(v)}`);
  }
}

/**
 * Builds the atlas for `usages` (the (texture, srgb) pairs the materials need), appending one
 * TextureInfo per pair to `heap`. Validates `textures` and `images` (INVALID_TEXTURE naming the
 * field); downscales a texture whose block exceeds `limits.maxTextureDimension2D` (warning naming
 * it, also pushed to `warnings`); throws SCENE_TOO_LARGE when the layers exceed
 * `limits.maxTextureArrayLayers`.
 */
export function buildTextureAtlas(
  scene: { readonly textures?: readonly WavefrontTextureInput[]; readonly images?: readonly WavefrontImageInput[] },
  usages: readonly TextureUsage[],
  heap: Vec4Heap,
  limits: AtlasLimits,
  warnings: string[] = [],
): TextureAtlas {
  validateLimits(limits);
  const textures = validateTextures(scene.textures, scene.images);
  const used = validateUsages(usages, textures.length);
  const limit = limits.maxTextureDimension2D;

  const blocks: Block[] = [];
  const blockOf = new Map<string, Block>();
  const imageIds = new Map<object, number>();
  const keyOf = (imageKey: object): number => {
    let id = imageIds.get(imageKey);
    if (id === undefined) imageIds.set(imageKey, (id = imageIds.size));
    return id;
  };
  const want = (t: number, encoding: TexelEncoding | 'raw', width: number, height: number, levels: number): Block => {
    const texture = textures[t]!;
    const key = `${keyOf(texture.imageKey)}|${width}x${height}|${levels}|${encoding}`;
    let block = blockOf.get(key);
    if (!block) {
      block = { imageKey: texture.imageKey, source: texture.image, width, height, levels, encoding, textures: new Set() };
      blockOf.set(key, block);
      blocks.push(block);
    }
    block.textures.add(t);
    return block;
  };

  // Mipmapped uses first, so that level-0-only uses can share their blocks.
  const blockOfUsage = new Map<TextureUsage, Block>();
  const mipmapped = (u: TextureUsage): boolean => samplerUsesMipmaps(textures[u.texture]!.sampler);
  for (const u of used.filter(mipmapped)) {
    const { image } = textures[u.texture]!;
    const fit = fitTextureToLimit(image.width, image.height, true, limit);
    const levels = fullMipCount(fit.width, fit.height);
    const downscaled = fit.halvings > 0;
    const encoding = levels > 1 || downscaled ? (u.srgb ? 'srgb' : 'linear') : 'raw';
    blockOfUsage.set(u, want(u.texture, encoding, fit.width, fit.height, levels));
  }
  for (const u of used.filter((x) => !mipmapped(x))) {
    const texture = textures[u.texture]!;
    const fit = fitTextureToLimit(texture.image.width, texture.image.height, false, limit);
    const downscaled = fit.halvings > 0;
    const encoding = downscaled ? (u.srgb ? 'srgb' : 'linear') : 'raw';
    // Level 0 of any block of this image at this size is the texture itself (in this encoding when downscaled).
    const shared = blocks.find(
      (b) => b.imageKey === texture.imageKey && b.width === fit.width && b.height === fit.height && (encoding === 'raw' || b.encoding === encoding),
    );
    if (shared) {
      shared.textures.add(u.texture);
      blockOfUsage.set(u, shared);
    } else {
      blockOfUsage.set(u, want(u.texture, encoding, fit.width, fit.height, 1));
    }
  }

  const ownWarnings: string[] = [];
  for (const b of blocks) {
    if (b.width === b.source.width && b.height === b.source.height) continue;
    const names = [...b.textures].sort((x, y) => x - y).map((t) => `textures[${t}]`).join(', ');
    const message = `${names}: ${b.source.width}x${b.source.height} downscaled to ${b.width}x${b.height} to fit maxTextureDimension2D ${limit}${b.levels > 1 ? ' with its mip chain' : ''}`;
    if (!ownWarnings.includes(message)) ownWarnings.push(message);
  }
  warnings.push(...ownWarnings);

  const layouts = blocks.map((b) => mipChainLayout(b.width, b.height, b.levels));
  const packing = packAtlas(
    layouts.map((l) => ({ width: l.blockWidth, height: l.blockHeight })),
    limits,
  );
  const size = packing.layerSize;
  const layers = Array.from({ length: packing.layerCount }, () => new Uint8Array(size * size * 4));
  blocks.forEach((b, i) => {
    const place = packing.placements[i]!;
    const encoding: TexelEncoding = b.encoding === 'raw' ? 'linear' : b.encoding;
    const base = b.width === b.source.width && b.height === b.source.height ? b.source : downscaleImage(b.source, b.width, b.height, encoding);
    const levels = imageMipChain(base, encoding, b.levels);
    layouts[i]!.levels.forEach((rect, k) => {
      const texels = levels[k]!;
      const layer = layers[place.layer]!;
      for (let y = 0; y < rect.height; y++) {
        const from = y * rect.width * 4;
        layer.set(texels.subarray(from, from + rect.width * 4), ((place.y + rect.y + y) * size + place.x + rect.x) * 4);
      }
    });
  });

  const blockIndex = new Map(blocks.map((b, i) => [b, i]));
  const offsets = new Map<string, number>();
  for (const u of used) {
    const b = blockOfUsage.get(u)!;
    const place = packing.placements[blockIndex.get(b)!]!;
    const offset = heap.append(textureInfoLayout, {
      origin: [place.x, place.y],
      size: [b.width, b.height],
      layer: place.layer,
      mipCount: b.levels,
      sampler: samplerBits(textures[u.texture]!.sampler),
    });
    offsets.set(`${u.texture}|${u.srgb}`, offset);
  }

  return {
    layerSize: size,
    layers,
    infoOffset(texture: number, srgb: boolean): number {
      const offset = offsets.get(`${texture}|${srgb === true}`);
      if (offset === undefined) throw new GpuRendererError('INVALID_STATE', `texture ${texture} (${srgb ? 'sRGB' : 'linear'}) was not among the atlas usages`);
      return offset;
    },
    bytes: size * size * 4 * packing.layerCount,
    textureCount: new Set(used.map((u) => u.texture)).size,
    blockCount: blocks.length,
    warnings: ownWarnings,
  };
}
