import { TextureUsage } from '../gpu/webgpu-constants.ts';
import type { EnvironmentMap } from './environment-map.ts';

/** The `environmentTexture` binding: the map's RGBA float32 texels, or a black 1 x 1 texture. */
export interface UploadedEnvironment {
  readonly texture: GPUTexture;
  readonly view: GPUTextureView;
  /** GPU memory of the texture in bytes. */
  readonly bytes: number;
}

/**
 * Uploads an environment map as an rgba32float texture (row 0 = the +Y zenith, as the map's data):
 * float32 keeps HDR suns above half float's 65504; the kernels filter it by hand, since rgba32float
 * is not filterable without an optional feature.
 */
export function uploadEnvironmentTexture(device: GPUDevice, map: EnvironmentMap | null): UploadedEnvironment {
  const width = map ? map.width : 1;
  const height = map ? map.height : 1;
  const texture = device.createTexture({
    label: 'environment map',
    size: { width, height, depthOrArrayLayers: 1 },
    format: 'rgba32float',
    dimension: '2d',
    usage: TextureUsage.TEXTURE_BINDING | TextureUsage.COPY_DST,
  });
  const data = map ? map.data : new Float32Array(4);
  // queue.writeTexture has no 256-byte row alignment rule (only buffer copies do); rows are tight.
  device.queue.writeTexture({ texture }, data, { offset: 0, bytesPerRow: width * 16, rowsPerImage: height }, { width, height, depthOrArrayLayers: 1 });
  return { texture, view: texture.createView({ dimension: '2d' }), bytes: width * height * 16 };
}
