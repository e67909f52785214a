import { BufferUsage, MapMode } from '../gpu/webgpu-constants.ts';
import { halfBitsToFloat32 } from '../math/half-float.ts';
import type { GpuRendererFormat, RendererPixels } from './renderer-types.ts';

/**
 * Copies a whole texture to a mappable buffer and returns tightly packed RGBA rows. Rows in the
 * staging buffer are padded to 256 bytes (WebGPU spec, GPUImageCopyBuffer bytesPerRow alignment).
 */
export async function readTexturePixels(device: GPUDevice, texture: GPUTexture, format: GpuRendererFormat): Promise<RendererPixels> {
  const { width, height } = texture;
  const texelBytes = format === 'rgba16float' ? 8 : 4;
  const bytesPerRow = Math.ceil((width * texelBytes) / 256) * 256;
  const staging = device.createBuffer({ size: bytesPerRow * height, usage: BufferUsage.MAP_READ | BufferUsage.COPY_DST });
  const encoder = device.createCommandEncoder({ label: 'gpu-renderer readPixels' });
  encoder.copyTextureToBuffer({ texture }, { buffer: staging, bytesPerRow, rowsPerImage: height }, { width, height });
  device.queue.submit([encoder.finish()]);
  await staging.mapAsync(MapMode.READ);
  const bytes = new Uint8Array(staging.getMappedRange().slice(0));
  staging.unmap();
  staging.destroy();
  if (format === 'rgba16float') {
    const data = new Float32Array(width * height * 4);
    const view = new DataView(bytes.buffer);
    for (let y = 0; y < height; y++) {
      for (let i = 0; i < width * 4; i++) data[y * width * 4 + i] = halfBitsToFloat32(view.getUint16(y * bytesPerRow + i * 2, true));
    }
    return { width, height, format, data };
  }
  const data = new Uint8Array(width * height * 4);
  const bgra = format === 'bgra8unorm';
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const s = y * bytesPerRow + x * 4;
      const d = (y * width + x) * 4;
      data[d] = bytes[bgra ? s + 2 : s]!;
      data[d + 1] = bytes[s + 1]!;
      data[d + 2] = bytes[bgra ? s : s + 2]!;
      data[d + 3] = bytes[s + 3]!;
    }
  }
  return { width, height, format, data };
}
