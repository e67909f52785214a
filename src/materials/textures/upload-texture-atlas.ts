/**
 * Uploads a packed atlas as the `textureAtlas` binding: one rgba8unorm 2d-array texture, a layer
 * per atlas layer (a 1x1x1 texture when there are no textures, since a binding cannot be empty).
 */
import { TextureUsage } from '../../gpu/webgpu-constants.ts';
import type { AtlasTexels } from './reference-sampler.ts';

export interface UploadedTextureAtlas {
  readonly texture: GPUTexture;
  /** A 2d-array view for the `textureAtlas` binding. */
  readonly view: GPUTextureView;
  /** GPU memory of the texture in bytes. */
  readonly bytes: number;
}

const bytesPerTexel = 4;

export function uploadTextureAtlas(device: GPUDevice, atlas: AtlasTexels, label = 'material texture atlas'): UploadedTextureAtlas {
  const empty = atlas.layers.length === 0;
  const size = empty ? 1 : atlas.layerSize;
  const layers = empty ? 1 : atlas.layers.length;
  const texture = device.createTexture({
    label,
    size: { width: size, height: size, depthOrArrayLayers: layers },
    format: 'rgba8unorm',
    dimension: '2d',
    usage: TextureUsage.TEXTURE_BINDING | TextureUsage.COPY_DST,
  });
  atlas.layers.forEach((texels, layer) => {
    if (texels.byteLength !== size * size * bytesPerTexel) throw new RangeError(`atlas layer ${layer} holds ${texels.byteLength} bytes, expected ${size * size * bytesPerTexel}`);
    // queue.writeTexture has no 256-byte row alignment rule (only buffer copies do); rows are tight.
    device.queue.writeTexture(
      { texture, origin: { x: 0, y: 0, z: layer } },
      texels,
      { offset: 0, bytesPerRow: size * bytesPerTexel, rowsPerImage: size },
      { width: size, height: size, depthOrArrayLayers: 1 },
    );
  });
  return { texture, view: texture.createView({ dimension: '2d-array' }), bytes: size * size * layers * bytesPerTexel };
}
