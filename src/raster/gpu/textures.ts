/**
 * Material textures of the raster renderer: each (texture, colour encoding) pair a material slot
 * uses becomes one GPU texture (rgba8unorm-srgb for colour slots, so the sampler filters in linear
 * light; rgba8unorm for data), with the shared CPU mip chain (area-weighted, sRGB-correct) when
 * its glTF sampler minifies with mipmaps, and a GPU sampler with the glTF sampler state.
 */
import { TextureUsage } from '../../gpu/webgpu-constants.ts';
import { fullMipCount } from '../../materials/textures/atlas-layout.ts';
import { fitTextureToLimit } from '../../materials/textures/atlas-packer.ts';
import { downscaleImage, imageMipChain, type Rgba8Image } from '../../materials/textures/mip-chain.ts';
import { samplerUsesMipmaps, type ResolvedSampler } from '../../materials/textures/sampler-state.ts';
import { validateTextures, type ValidatedTexture } from '../../materials/textures/texture-input.ts';
import type { WavefrontImageInput, WavefrontTextureInput, WavefrontWrapMode } from '../../scene/types.ts';
import type { RasterMaterial } from '../scene/raster-material.ts';
import { rasterTextureSlots } from './raster-layout.ts';


export interface RasterTextures {
  view(texture: number, srgb: boolean): GPUTextureView;
  sampler(texture: number): GPUSampler;
  readonly fallbackView: GPUTextureView;
  readonly fallbackSampler: GPUSampler;
  readonly bytes: number;
  readonly count: number;
  destroy(): void;
}

const addressMode: Record<WavefrontWrapMode, GPUAddressMode> = { repeat: 'repeat', 'clamp-to-edge': 'clamp-to-edge', 'mirrored-repeat': 'mirror-repeat' };

function samplerDescriptor(s: ResolvedSampler): GPUSamplerDescriptor {
  const mipmaps = samplerUsesMipmaps(s);
  const min = s.minFilter;
  return {
    addressModeU: addressMode[s.wrapS],
    addressModeV: addressMode[s.wrapT],
    magFilter: s.magFilter,
    minFilter: min === 'nearest' || min.startsWith('nearest-') ? 'nearest' : 'linear',
    mipmapFilter: min.endsWith('-mipmap-linear') ? 'linear' : 'nearest',
    lodMaxClamp: mipmaps ? 32 : 0,
    maxAnisotropy: 1,
  };
}

function uploadImage(device: GPUDevice, image: Rgba8Image, srgb: boolean, mipmaps: boolean): { texture: GPUTexture; bytes: number } {
  const limit = device.limits.maxTextureDimension2D;
  const fit = fitTextureToLimit(image.width, image.height, mipmaps, limit);
  const base = fit.width === image.width && fit.height === image.height ? image : downscaleImage(image, fit.width, fit.height, srgb ? 'srgb' : 'linear');
  const levels = mipmaps ? fullMipCount(base.width, base.height) : 1;
  const texture = device.createTexture({
    label: 'raster material texture',
    size: { width: base.width, height: base.height },
    mipLevelCount: levels,
    format: srgb ? 'rgba8unorm-srgb' : 'rgba8unorm',
    usage: TextureUsage.TEXTURE_BINDING | TextureUsage.COPY_DST,
  });
  const chain = mipmaps ? imageMipChain(base, srgb ? 'srgb' : 'linear', levels) : [base.data];
  let bytes = 0;
  chain.forEach((data, level) => {
    const w = Math.max(1, base.width >> level);
    const h = Math.max(1, base.height >> level);
    device.queue.writeTexture({ texture, mipLevel: level }, data, { bytesPerRow: 4 * w, rowsPerImage: h }, { width: w, height: h });
    bytes += data.byteLength;
  });
  return { texture, bytes };
}

export function createRasterTextures(
  device: GPUDevice,
  input: { textures?: readonly WavefrontTextureInput[]; images?: readonly WavefrontImageInput[] },
  materials: readonly RasterMaterial[],
): RasterTextures {
  const validated: ValidatedTexture[] = validateTextures(input.textures, input.images);
  const wanted = new Set<string>();
  for (const m of materials) {
    for (const slot of rasterTextureSlots) {
      const ref = m.textures[slot.name];
      if (ref !== undefined) wanted.add(`${ref.texture}:${slot.srgb ? 1 : 0}`);
    }
  }
  const textures = new Map<string, GPUTexture>();
  const byImage = new Map<string, GPUTexture>();
  let bytes = 0;
  for (const key of wanted) {
    const [t, s] = key.split(':').map(Number) as [number, number];
    const v = validated[t]!;
    const mipmaps = samplerUsesMipmaps(v.sampler);
    // Textures sharing one image (and encoding and mip need) share its GPU texture.
    const imageKey = `${validated.findIndex((o) => o.imageKey === v.imageKey)}:${s}:${mipmaps ? 1 : 0}`;
    let texture = byImage.get(imageKey);
    if (texture === undefined) {
      const uploaded = uploadImage(device, v.image, s === 1, mipmaps);
      texture = uploaded.texture;
      bytes += uploaded.bytes;
      byImage.set(imageKey, texture);
    }
    textures.set(key, texture);
  }
  const samplers = validated.map((v) => device.createSampler(samplerDescriptor(v.sampler)));
  const fallback = device.createTexture({ label: 'raster fallback texture', size: { width: 1, height: 1 }, format: 'rgba8unorm', usage: TextureUsage.TEXTURE_BINDING | TextureUsage.COPY_DST });
  device.queue.writeTexture({ texture: fallback }, new Uint8Array([255, 255, 255, 255]), { bytesPerRow: 4 }, { width: 1, height: 1 });
  const fallbackView = fallback.createView();
  const fallbackSampler = device.createSampler({});
  const views = new Map<string, GPUTextureView>();
  return {
    view(texture, srgb) {
      const key = `${texture}:${srgb ? 1 : 0}`;
      let view = views.get(key);
      if (view === undefined) {
        const t = textures.get(key);
        view = t === undefined ? fallbackView : t.createView();
        views.set(key, view);
      }
      return view;
    },
    sampler: (texture) => samplers[texture] ?? fallbackSampler,
    fallbackView,
    fallbackSampler,
    bytes,
    count: byImage.size,
    destroy() {
      for (const t of byImage.values()) t.destroy();
      fallback.destroy();
    },
  };
}
