import { encode } from 'fast-png';
import { GpuRendererError } from '../../errors/gpu-renderer-error.ts';

export interface Rgba8Image {
  width: number;
  height: number;
  /** RGBA8, row-major, top row first (the layout of readPixels()). */
  data: Uint8ClampedArray | Uint8Array;
}

/** Encodes an RGBA8 image as a PNG file (8-bit RGBA, via fast-png). Works in browsers and Node.js. */
export function encodePng(image: Rgba8Image): Uint8Array {
  const { width, height, data } = image;
  if (!Number.isInteger(width) || width < 1) throw new GpuRendererError('INVALID_OPTION', `expected a positive integer, got ${width}`, { field: 'width' });
  if (!Number.isInteger(height) || height < 1) {
    throw new GpuRendererError('INVALID_OPTION', `expected a positive integer, got ${height}`, { field: 'height' });
  }
  if (!(data instanceof Uint8ClampedArray || data instanceof Uint8Array) || data.length !== width * height * 4) {
    throw new GpuRendererError('INVALID_OPTION', `expected ${width * height * 4} RGBA8 bytes`, { field: 'data' });
  }
  // The PNG stores no colour chunk, so readers assume sRGB, which is what readPixels() produces.
  return encode({ width, height, data, depth: 8, channels: 4 });
}
