/**
 * One entry point for writing a rendered image: the format follows the file extension (or
 * `options.format`). PNG is display-referred (tone mapped, exposed, sRGB 8-bit); OpenEXR and
 * Radiance HDR are scene-referred and store the radiance exactly as rendered (tone mapping and
 * exposure options do not apply to them).
 */
import { GpuRendererError } from '../../errors/gpu-renderer-error.ts';
import { writeFileBytes } from '../platform.ts';
import { encodePng } from './png.ts';
import { encodeRadianceToRgba8, type EncodeRadianceOptions } from '../../film/tone-mapping.ts';
import { encodeExr, type EncodeExrOptions } from './exr-encode.ts';
import { encodeHdr, type EncodeHdrOptions } from './hdr-encode.ts';
import { requireLinearRgbaImage, type LinearRgbaImage } from './linear-image.ts';

export type ImageFileFormat = 'png' | 'exr' | 'hdr';

export const imageFileFormats: readonly ImageFileFormat[] = Object.freeze(['png', 'exr', 'hdr'] as ImageFileFormat[]);

export interface ImageFileOptions extends EncodeExrOptions, EncodeRadianceOptions, EncodeHdrOptions {
  /** Overrides the format the file extension implies. */
  format?: ImageFileFormat;
}

/** The format a path's extension names (.png, .exr, .hdr; any case); a typed error otherwise. */
export function imageFileFormatFromPath(path: string): ImageFileFormat {
  const match = /\.([A-Za-z]+)$/.exec(typeof path === 'string' ? path : '');
  const ext = match?.[1].toLowerCase();
  if (ext === 'png' || ext === 'exr' || ext === 'hdr') return ext;
  throw new GpuRendererError('INVALID_OPTION', `cannot tell the image format from ${JSON.stringify(path)} (expected .png, .exr or .hdr, or pass format)`, {
    field: 'path',
  });
}

/** Encodes `image` in `format`; browser-safe (no file system). */
export function encodeImageFile(image: LinearRgbaImage, format: ImageFileFormat, options: ImageFileOptions = {}): Uint8Array {
  requireLinearRgbaImage(image);
  if (format !== 'exr') {
    const layers = Object.values(options.aovs ?? {}).some((v) => v !== undefined) || (options.layers?.length ?? 0) > 0;
    if (layers) {
      throw new GpuRendererError('INVALID_OPTION', `${format.toUpperCase()} files hold one RGB image; write AOVs and layers to an .exr file`, {
        field: options.aovs ? 'aovs' : 'layers',
      });
    }
  }
  switch (format) {
    case 'png':
      return encodePng({ width: image.width, height: image.height, data: encodeRadianceToRgba8(image.data, options) });
    case 'exr':
      return encodeExr(image, options);
    case 'hdr':
      return encodeHdr(image, options);
    default:
      throw new GpuRendererError('INVALID_OPTION', `expected one of ${imageFileFormats.join(', ')}, got ${JSON.stringify(format)}`, { field: 'format' });
  }
}

/**
 * Encodes `image` and writes it to `path` (Node.js only), choosing the format from the extension
 * unless `options.format` is given (browser bundles never resolve `node:fs`). Resolves to the format and the number of bytes written.
 */
export async function writeImageFile(path: string, image: LinearRgbaImage, options: ImageFileOptions = {}): Promise<{ format: ImageFileFormat; bytes: number }> {
  const format = options.format ?? imageFileFormatFromPath(path);
  const bytes = encodeImageFile(image, format, options);
  await writeFileBytes(path, bytes, 'writeImageFile', 'use encodeImageFile, encodeExr or encodeHdr in browsers');
  return { format, bytes: bytes.length };
}
