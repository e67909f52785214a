/**
 * Packs texture blocks (a mip chain each, see atlas-layout.ts) into the square layers of one
 * texture array. Blocks need no gutter: texture-sampling.wesl wraps and filters every texture with
 * textureLoad inside its own levels, so neighbours never bleed into each other.
 */
import { GpuRendererError } from '../../errors/gpu-renderer-error.ts';
import { fullMipCount, mipBlockSize } from './atlas-layout.ts';

/** The device limits the atlas must respect (a GPUSupportedLimits will do). */
export interface AtlasLimits {
  readonly maxTextureDimension2D: number;
  readonly maxTextureArrayLayers: number;
}

export interface BlockSize {
  readonly width: number;
  readonly height: number;
}

export interface BlockPlacement {
  readonly layer: number;
  readonly x: number;
  readonly y: number;
}

export interface AtlasPacking {
  /** Side of every layer, in texels (1 when there is nothing to pack). */
  readonly layerSize: number;
  readonly layerCount: number;
  /** Where each block went, in the order the blocks were given. */
  readonly placements: readonly BlockPlacement[];
}

interface Shelf {
  readonly layer: number;
  readonly y: number;
  readonly height: number;
  usedWidth: number;
}

/**
 * First-fit decreasing-height shelf packing (Coffman et al., "Performance bounds for
 * level-oriented two-dimensional packing algorithms", SIAM J. Comput. 9(4), 1980) into as many
 * `size` x `size` layers as it takes. Blocks go tallest first (ties: wider first, then input order,
 * so the result is deterministic) into the first shelf with room, else onto a new shelf in the
 * first layer with room, else into a new layer.
 */
export function shelfPack(blocks: readonly BlockSize[], size: number): { placements: BlockPlacement[]; layerCount: number } {
  const order = blocks.map((_, i) => i).sort((a, b) => blocks[b]!.height - blocks[a]!.height || blocks[b]!.width - blocks[a]!.width || a - b);
  const shelves: Shelf[] = [];
  const layerHeights: number[] = [];
  const placements: BlockPlacement[] = new Array<BlockPlacement>(blocks.length);
  for (const i of order) {
    const { width, height } = blocks[i]!;
    if (width > size || height > size) throw new RangeError(`block ${i} (${width}x${height}) is larger than the ${size}x${size} layer`);
    let shelf = shelves.find((s) => s.height >= height && size - s.usedWidth >= width);
    if (!shelf) {
      let layer = layerHeights.findIndex((used) => size - used >= height);
      if (layer < 0) {
        layer = layerHeights.length;
        layerHeights.push(0);
      }
      shelf = { layer, y: layerHeights[layer]!, height, usedWidth: 0 };
      layerHeights[layer]! += height;
      shelves.push(shelf);
    }
    placements[i] = { layer: shelf.layer, x: shelf.usedWidth, y: shelf.y };
    shelf.usedWidth += width;
  }
  return { placements, layerCount: layerHeights.length };
}

/** Layer sides worth trying: powers of two from the largest block side up to the limit (the limit itself when no power of two fits). */
function candidateSizes(largest: number, limit: number): number[] {
  const sizes: number[] = [];
  let size = 1;
  while (size < largest) size *= 2;
  for (; size <= limit; size *= 2) sizes.push(size);
  if (sizes.length === 0) sizes.push(limit);
  return sizes;
}

/**
 * Chooses the layer side and packs: among the powers of two from the largest block side up to
 * `maxTextureDimension2D`, the one whose packing takes the fewest texels in all (layer area x
 * layers), ties going to fewer layers. A size that fits everything into one layer ends the
 * search, since every larger one costs more. Throws SCENE_TOO_LARGE (field `textures`) when even
 * the largest layers need more than `maxTextureArrayLayers`.
 */
export function packAtlas(blocks: readonly BlockSize[], limits: AtlasLimits): AtlasPacking {
  if (blocks.length === 0) return { layerSize: 1, layerCount: 0, placements: [] };
  const limit = limits.maxTextureDimension2D;
  const largest = Math.max(...blocks.map((b) => Math.max(b.width, b.height)));
  if (largest > limit) throw new RangeError(`a ${largest}-texel block exceeds maxTextureDimension2D ${limit}; fit it first (fitTextureToLimit)`);
  let best: { size: number; packed: ReturnType<typeof shelfPack>; texels: number } | undefined;
  let fewestLayers = Infinity;
  for (const size of candidateSizes(largest, limit)) {
    const packed = shelfPack(blocks, size);
    fewestLayers = Math.min(fewestLayers, packed.layerCount);
    const texels = size * size * packed.layerCount;
    const better = !best || texels < best.texels || (texels === best.texels && packed.layerCount < best.packed.layerCount);
    if (packed.layerCount <= limits.maxTextureArrayLayers && better) best = { size, packed, texels };
    if (packed.layerCount === 1) break;
  }
  if (!best) {
    throw new GpuRendererError(
      'SCENE_TOO_LARGE',
      `the textures need ${fewestLayers} atlas layers of at most ${limit}x${limit} texels, but the device allows ${limits.maxTextureArrayLayers} (maxTextureArrayLayers)`,
      { field: 'textures' },
    );
  }
  return { layerSize: best.size, layerCount: best.packed.layerCount, placements: best.packed.placements };
}

/**
 * The level-0 size at which a `width` x `height` texture's block (with its mip chain when
 * `mipmapped`) fits in a `limit`-texel layer: the image halves (WebGPU's floor rule, like a mip
 * level) until it does. Returns the size and how many halvings it took.
 */
export function fitTextureToLimit(width: number, height: number, mipmapped: boolean, limit: number): { width: number; height: number; halvings: number } {
  for (let halvings = 0; ; halvings++) {
    const w = Math.max(1, width >> halvings);
    const h = Math.max(1, height >> halvings);
    const [bw, bh] = mipBlockSize(w, h, mipmapped ? fullMipCount(w, h) : 1);
    if (bw <= limit && bh <= limit) return { width: w, height: h, halvings };
    if (w === 1 && h === 1) throw new RangeError(`a 1x1 texture does not fit in a ${limit}-texel layer`);
  }
}
