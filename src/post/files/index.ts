export { encodeExr, type EncodeExrOptions, type ExrCompression, type ExrLayer, type ExrPixelType } from './exr-encode.ts';
export { encodeHdr, encodeRgbe, type EncodeHdrOptions } from './hdr-encode.ts';
export { decodeHdr } from './hdr-decode.ts';
export { float32ToHalfBits, halfBitsToFloat32 } from './half-float.ts';
export {
  encodeImageFile,
  imageFileFormatFromPath,
  imageFileFormats,
  writeImageFile,
  type ImageFileFormat,
  type ImageFileOptions,
} from './image-file.ts';
export type { LinearRgbaImage } from './linear-image.ts';
