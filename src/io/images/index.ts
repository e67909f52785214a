// Image files in both directions: PNG, OpenEXR and Radiance HDR writers, the HDR and OpenEXR readers.
export { encodeExr, type EncodeExrOptions, type ExrCompression, type ExrLayer, type ExrPixelType } from './exr-encode.ts';
export { encodeHdr, encodeRgbe, type EncodeHdrOptions } from './hdr-encode.ts';
export { decodeHdr, decodeRadianceHdr, isRadianceHdr, type DecodeRadianceHdrOptions, type DecodedHdrImage } from './radiance-hdr.ts';
export { decodeOpenExr, isOpenExr, type DecodeOpenExrOptions, type ExrLoaderLike, type ExrLoaderConstructor } from './openexr.ts';
export { float32ToHalfBits, halfBitsToFloat32 } from '../../math/half-float.ts';
export { encodePng, type Rgba8Image } from './png.ts';
export { writePng } from './png-node.ts';
export {
  encodeImageFile,
  imageFileFormatFromPath,
  imageFileFormats,
  writeImageFile,
  type ImageFileFormat,
  type ImageFileOptions,
} from './image-file.ts';
export type { LinearRgbaImage } from './linear-image.ts';
