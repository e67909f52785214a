/**
 * Where a texture's mip chain lies inside its atlas block, mirrored from texture-sampling.wesl
 * (`mip_size`, `mip_origin`): level 0 at the block origin, every level k >= 1 in one column to its
 * right, at x = width, y = the summed heights of levels 1..k-1. Level sizes follow WebGPU's
 * convention, max(1, size >> k) (WebGPU spec, "logical miplevel-specific texture extent").
 */

/** A rectangle in texels, relative to the block origin. */
export interface TexelRect {
  readonly x: number;
  readonly y: number;
  readonly width: number;
  readonly height: number;
}

export interface MipChainLayout {
  readonly levels: readonly TexelRect[];
  readonly blockWidth: number;
  readonly blockHeight: number;
}

/** floor(log2(max(width, height))) + 1: the full chain down to 1x1. */
export function fullMipCount(width: number, height: number): number {
  return 32 - Math.clz32(Math.max(width, height));
}

/** Size of `level` (WebGPU: each dimension halves with floor, never below 1). */
export function mipLevelSize(width: number, height: number, level: number): [number, number] {
  return [Math.max(1, width >> level), Math.max(1, height >> level)];
}

/** Origin of `level` relative to the block origin (texture-sampling.wesl `mip_origin`). */
export function mipLevelOrigin(width: number, height: number, level: number): [number, number] {
  if (level === 0) return [0, 0];
  let y = 0;
  for (let k = 1; k < level; k++) y += Math.max(1, height >> k);
  return [width, y];
}

/** Block size of a chain of `levels` levels: level 0 beside the column of the smaller levels. */
export function mipBlockSize(width: number, height: number, levels: number): [number, number] {
  if (levels <= 1) return [width, height];
  let column = 0;
  for (let k = 1; k < levels; k++) column += Math.max(1, height >> k);
  return [width + Math.max(1, width >> 1), Math.max(height, column)];
}

/** Every level's rectangle and the block that holds them. */
export function mipChainLayout(width: number, height: number, levels: number = fullMipCount(width, height)): MipChainLayout {
  const rects: TexelRect[] = [];
  for (let k = 0; k < levels; k++) {
    const [x, y] = mipLevelOrigin(width, height, k);
    const [w, h] = mipLevelSize(width, height, k);
    rects.push({ x, y, width: w, height: h });
  }
  const [blockWidth, blockHeight] = mipBlockSize(width, height, levels);
  return { levels: rects, blockWidth, blockHeight };
}
