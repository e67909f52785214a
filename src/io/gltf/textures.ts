/**
 * The scene's `images` and `textures` tables. @gltf-transform models a glTF image as a `Texture`
 * and keeps sampler state on each material slot's `TextureInfo`; here every image used by a
 * material is decoded once into `images`, and every distinct (image, sampler) pair becomes one
 * entry of `textures`. GL enums become the named modes of types.ts (glTF 2.0 section 5.26).
 */
import type { Texture, TextureInfo } from '@gltf-transform/core';
import type { Transform } from '@gltf-transform/extensions';
import type {
  WavefrontImageInput,
  WavefrontMagFilter,
  WavefrontMinFilter,
  WavefrontSamplerInput,
  WavefrontTextureInput,
  WavefrontTextureRefInput,
  WavefrontTextureTransformInput,
  WavefrontWrapMode,
} from '../../scene/types.ts';
import { failGltf, pointer } from './errors.ts';
import { decodeImage } from './image-decoding.ts';
import type { ResolvedResourcePolicy } from '../resource-policy.ts';

const WRAP: Readonly<Record<number, WavefrontWrapMode>> = { 10497: 'repeat', 33071: 'clamp-to-edge', 33648: 'mirrored-repeat' };
const MAG: Readonly<Record<number, WavefrontMagFilter>> = { 9728: 'nearest', 9729: 'linear' };
const MIN: Readonly<Record<number, WavefrontMinFilter>> = {
  9728: 'nearest',
  9729: 'linear',
  9984: 'nearest-mipmap-nearest',
  9985: 'linear-mipmap-nearest',
  9986: 'nearest-mipmap-linear',
  9987: 'linear-mipmap-linear',
};

export function samplerFromTextureInfo(info: TextureInfo): WavefrontSamplerInput {
  const sampler: WavefrontSamplerInput = { wrapS: WRAP[info.getWrapS()] ?? 'repeat', wrapT: WRAP[info.getWrapT()] ?? 'repeat' };
  const mag = info.getMagFilter();
  const min = info.getMinFilter();
  if (mag !== null && MAG[mag] !== undefined) sampler.magFilter = MAG[mag];
  if (min !== null && MIN[min] !== undefined) sampler.minFilter = MIN[min];
  return sampler;
}

/** KHR_texture_transform on a slot, if any. */
export function textureTransform(info: TextureInfo): WavefrontTextureTransformInput | undefined {
  const ext = info.getExtension<Transform>('KHR_texture_transform');
  if (ext === null) return undefined;
  const transform: WavefrontTextureTransformInput = { offset: [...ext.getOffset()], rotation: ext.getRotation(), scale: [...ext.getScale()] };
  const texCoord = ext.getTexCoord();
  if (texCoord !== null && texCoord !== undefined) transform.texCoord = texCoord;
  return transform;
}

export class TextureTable {
  readonly images: WavefrontImageInput[] = [];
  readonly textures: WavefrontTextureInput[] = [];
  private readonly imageIndex = new Map<Texture, Promise<number>>();
  /** Images computed from decoded ones (derivedReference), by the image's index and the derivation's key. */
  private readonly derivedIndex = new Map<string, number>();
  private readonly textureIndex = new Map<string, number>();
  private readonly allImages: readonly Texture[];
  private readonly warnings: string[];
  private readonly policy: ResolvedResourcePolicy | undefined;

  constructor(allImages: readonly Texture[], warnings: string[], policy?: ResolvedResourcePolicy) {
    this.allImages = allImages;
    this.warnings = warnings;
    this.policy = policy;
  }

  /** Decodes the image once. */
  private image(texture: Texture): Promise<number> {
    let pending = this.imageIndex.get(texture);
    if (pending === undefined) {
      pending = this.decode(texture);
      this.imageIndex.set(texture, pending);
    }
    return pending;
  }

  private async decode(texture: Texture): Promise<number> {
    const at = pointer('images', this.allImages.indexOf(texture));
    const bytes = texture.getImage();
    // Unreadable external images were rejected while reading the asset; this is a Document passed
    // in whose image was never loaded.
    if (bytes === null) failGltf(at, `the image has no data${texture.getURI() ? ` (${texture.getURI()})` : ''}`);
    const { image, notes } = await decodeImage(bytes, at, this.policy);
    for (const note of notes) this.warnings.push(`${at}: ${note}`);
    this.images.push(image);
    return this.images.length - 1;
  }

  /** The reference a material slot makes to `texture` through `info`; undefined without one, or (warned) when it cannot. */
  async reference(texture: Texture | null, info: TextureInfo | null, slotAt: string): Promise<WavefrontTextureRefInput | undefined> {
    return this.referenceTo(texture, info, slotAt, undefined);
  }

  /**
   * Like `reference`, to an image computed from the decoded image by `derive` (same size, RGBA8,
   * top row first), made once per image and `key`: e.g. a roughness channel baked from glossiness.
   */
  async derivedReference(
    texture: Texture | null,
    info: TextureInfo | null,
    slotAt: string,
    key: string,
    derive: (source: WavefrontImageInput) => WavefrontImageInput,
  ): Promise<WavefrontTextureRefInput | undefined> {
    return this.referenceTo(texture, info, slotAt, { key, derive });
  }

  private async referenceTo(
    texture: Texture | null,
    info: TextureInfo | null,
    slotAt: string,
    derived: { key: string; derive: (source: WavefrontImageInput) => WavefrontImageInput } | undefined,
  ): Promise<WavefrontTextureRefInput | undefined> {
    if (texture === null || info === null) return undefined;
    let image = await this.image(texture);
    if (derived !== undefined) {
      const derivedKey = `${image}|${derived.key}`;
      let index = this.derivedIndex.get(derivedKey);
      if (index === undefined) {
        index = this.images.push(derived.derive(this.images[image]!)) - 1;
        this.derivedIndex.set(derivedKey, index);
      }
      image = index;
    }
    const transform = textureTransform(info);
    const texCoord = transform?.texCoord ?? info.getTexCoord();
    if (texCoord > 1) {
      this.warnings.push(`${slotAt}: texture dropped (TEXCOORD_${texCoord}; only TEXCOORD_0 and TEXCOORD_1 are loaded)`);
      return undefined;
    }
    const sampler = samplerFromTextureInfo(info);
    const key = `${image}|${sampler.wrapS}|${sampler.wrapT}|${sampler.magFilter}|${sampler.minFilter}`;
    let index = this.textureIndex.get(key);
    if (index === undefined) {
      index = this.textures.length;
      const entry: WavefrontTextureInput = { image, sampler };
      if (texture.getName() !== '') entry.name = texture.getName();
      this.textures.push(entry);
      this.textureIndex.set(key, index);
    }
    const ref: WavefrontTextureRefInput = { index, texCoord: info.getTexCoord() };
    if (transform !== undefined) ref.transform = transform;
    return ref;
  }
}
