import { GpuRendererError } from '../../errors/gpu-renderer-error.ts';

/**
 * Linear scene-referred radiance, RGBA float32, row-major, top row first: the layout of the
 * renderer's `readRadiance()` (alpha is coverage, 1 for every rendered pixel).
 */
export interface LinearRgbaImage {
  width: number;
  height: number;
  data: Float32Array;
}

/** Checks width, height and the RGBA length; returns the pixel count. */
export function requireLinearRgbaImage(image: LinearRgbaImage, field = 'image'): number {
  if (image === null || typeof image !== 'object') throw new GpuRendererError('INVALID_OPTION', 'expected an image object', { field });
  const { width, height, data } = image;
  if (!Number.isInteger(width) || width < 1) throw new GpuRendererError('INVALID_OPTION', `expected a positive integer, got ${String(width)}`, { field: `${field}.width` });
  if (!Number.isInteger(height) || height < 1) {
    throw new GpuRendererError('INVALID_OPTION', `expected a positive integer, got ${String(height)}`, { field: `${field}.height` });
  }
  if (!(data instanceof Float32Array) || data.length !== width * height * 4) {
    throw new GpuRendererError('INVALID_OPTION', `expected a Float32Array of ${width * height * 4} RGBA values`, { field: `${field}.data` });
  }
  return width * height;
}
