/**
 * Validation of the scene's `textures` and `images` (the public input): every fault is a typed
 * INVALID_TEXTURE error whose field names the offending path (`images[1].data`,
 * `textures[2].sampler.wrapS`).
 */
import { describe, fail, isArrayLike } from '../../errors/validate.ts';
import type { WavefrontImageInput, WavefrontTextureInput } from '../../scene/types.ts';
import { fullMipCount, mipLevelSize } from './atlas-layout.ts';
import type { Rgba8Image } from './mip-chain.ts';
import { resolveSampler, type ResolvedSampler } from './sampler-state.ts';

export interface ValidatedTexture {
  /** The image object itself: textures naming the same image share its atlas blocks. */
  readonly image: Rgba8Image;
  readonly imageKey: object;
  readonly sampler: ResolvedSampler;
}

function requireSize(value: unknown, field: string): number {
  if (typeof value !== 'number' || !Number.isInteger(value) || value < 1) fail('INVALID_TEXTURE', field, `expected an integer >= 1, got ${describe(value)}`);
  return value;
}

/** Checks one image and returns it with its texels as a Uint8Array (a view, not a copy, when possible). */
export function validateImage(input: unknown, field: string): Rgba8Image {
  if (input === null || typeof input !== 'object') fail('INVALID_TEXTURE', field, `expected an image { width, height, data }, got ${describe(input)}`);
  const { width, height, data } = input as Partial<WavefrontImageInput>;
  const w = requireSize(width, `${field}.width`);
  const h = requireSize(height, `${field}.height`);
  const expected = w * h * 4;
  if (!isArrayLike(data)) fail('INVALID_TEXTURE', `${field}.data`, `expected RGBA8 texels (a Uint8Array), got ${describe(data)}`);
  if (data.length !== expected) fail('INVALID_TEXTURE', `${field}.data`, `expected ${w} x ${h} x 4 = ${expected} bytes, got ${data.length}`);
  const mipLevels = validateMipLevels((input as Partial<WavefrontImageInput>).mipLevels, w, h, `${field}.mipLevels`);
  if (data instanceof Uint8Array || data instanceof Uint8ClampedArray) {
    return { width: w, height: h, data: new Uint8Array(data.buffer, data.byteOffset, data.byteLength), ...(mipLevels ? { mipLevels } : {}) };
  }
  const bytes = new Uint8Array(expected);
  for (let i = 0; i < expected; i++) {
    const v = (data as ArrayLike<unknown>)[i];
    if (typeof v !== 'number' || !Number.isInteger(v) || v < 0 || v > 255) fail('INVALID_TEXTURE', `${field}.data[${i}]`, `expected a byte (integer 0..255), got ${describe(v)}`);
    bytes[i] = v;
  }
  return { width: w, height: h, data: bytes, ...(mipLevels ? { mipLevels } : {}) };
}

/** Stored mip levels 1, 2, ...: each of its level's size (atlas-layout.ts mipLevelSize), at most down to 1 x 1. */
function validateMipLevels(input: unknown, width: number, height: number, field: string): Rgba8Image[] | undefined {
  if (input === undefined) return undefined;
  if (!Array.isArray(input)) fail('INVALID_TEXTURE', field, `expected an array of images, got ${describe(input)}`);
  const most = fullMipCount(width, height) - 1;
  if (input.length > most) fail('INVALID_TEXTURE', field, `a ${width} x ${height} image has ${most} levels below level 0, got ${input.length}`);
  return input.map((level: unknown, k) => {
    const image = validateImage(level, `${field}[${k}]`);
    const [w, h] = mipLevelSize(width, height, k + 1);
    if (image.width !== w || image.height !== h) fail('INVALID_TEXTURE', `${field}[${k}]`, `level ${k + 1} of a ${width} x ${height} image is ${w} x ${h}, got ${image.width} x ${image.height}`);
    if (image.mipLevels !== undefined) fail('INVALID_TEXTURE', `${field}[${k}].mipLevels`, 'a mip level has no levels of its own');
    return image;
  });
}

/** Validates every image and texture (used or not); texture i of the result is textures[i]. */
export function validateTextures(textures: readonly WavefrontTextureInput[] | undefined, images: readonly WavefrontImageInput[] | undefined): ValidatedTexture[] {
  if (images !== undefined && !Array.isArray(images)) fail('INVALID_TEXTURE', 'images', `expected an array, got ${describe(images)}`);
  if (textures !== undefined && !Array.isArray(textures)) fail('INVALID_TEXTURE', 'textures', `expected an array, got ${describe(textures)}`);
  const sharedImages = (images ?? []).map((image, i) => validateImage(image, `images[${i}]`));
  return (textures ?? []).map((texture, t) => {
    const field = `textures[${t}]`;
    if (texture === null || typeof texture !== 'object') fail('INVALID_TEXTURE', field, `expected a texture { image, sampler? }, got ${describe(texture)}`);
    const ref: unknown = texture.image;
    let image: Rgba8Image;
    let imageKey: object;
    if (typeof ref === 'number') {
      if (!Number.isInteger(ref) || ref < 0 || ref >= sharedImages.length) {
        fail('INVALID_TEXTURE', `${field}.image`, `expected an index into images (which has ${sharedImages.length} entries), got ${ref}`);
      }
      image = sharedImages[ref]!;
      imageKey = images![ref]!;
    } else {
      image = validateImage(ref, `${field}.image`);
      imageKey = ref as object;
    }
    return { image, imageKey, sampler: resolveSampler(texture.sampler, `${field}.sampler`) };
  });
}
