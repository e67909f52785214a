// Hand-built atlases for the sampler tests: a texture's levels written into one layer at a chosen
// origin, everything else in the layer filled with a "poison" colour, so a read outside the
// texture's own levels shows.
import { mipChainLayout } from '../../../src/materials/textures/atlas-layout.ts';
import type { AtlasTexels, TextureInfoRecord } from '../../../src/materials/textures/reference-sampler.ts';

export interface HandAtlas {
  atlas: AtlasTexels;
  info: TextureInfoRecord;
}

/** Levels given as RGBA8 arrays of the WebGPU level sizes of a width x height texture. */
export function handAtlas(width: number, height: number, levels: readonly Uint8Array[], sampler: number, poison: readonly number[] = [255, 0, 255, 255]): HandAtlas {
  const layout = mipChainLayout(width, height, levels.length);
  const origin: [number, number] = [2, 3];
  const layerSize = Math.max(layout.blockWidth, layout.blockHeight) + 6;
  const layer = new Uint8Array(layerSize * layerSize * 4);
  for (let i = 0; i < layer.length; i++) layer[i] = poison[i % 4]!;
  layout.levels.forEach((r, k) => {
    const texels = levels[k]!;
    if (texels.length !== r.width * r.height * 4) throw new Error(`level ${k} must be ${r.width}x${r.height}`);
    for (let y = 0; y < r.height; y++) {
      layer.set(texels.subarray(y * r.width * 4, (y + 1) * r.width * 4), ((origin[1] + r.y + y) * layerSize + origin[0] + r.x) * 4);
    }
  });
  return { atlas: { layerSize, layers: [layer] }, info: { origin, size: [width, height], layer: 0, mipCount: levels.length, sampler } };
}

/** A w x h level whose every texel is `rgba`. */
export function constantLevel(w: number, h: number, rgba: readonly number[]): Uint8Array {
  return Uint8Array.from({ length: w * h * 4 }, (_, i) => rgba[i % 4]!);
}
