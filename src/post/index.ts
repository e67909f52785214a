export {
  toneMapPbrNeutral,
  toneMapAces,
  toneMapAgx,
  agxContrastApprox,
  agxMinEv,
  agxMaxEv,
  linearToSrgb,
  srgbToLinear,
  applyToneMapping,
  encodeRadianceToRgba8,
  exposureMultiplier,
  isToneMapping,
  toneMappingModeIds,
  toneMappingNames,
  type EncodeRadianceOptions,
  type Rgb,
  type ToneMappingMode,
} from './tone-mapping.ts';
// Image files live in src/io/images; re-exported here, where they were first published.
export {
  encodePng,
  writePng,
  encodeExr,
  encodeHdr,
  encodeRgbe,
  decodeHdr,
  float32ToHalfBits,
  halfBitsToFloat32,
  encodeImageFile,
  imageFileFormatFromPath,
  imageFileFormats,
  writeImageFile,
  type Rgba8Image,
  type EncodeExrOptions,
  type ExrCompression,
  type ExrLayer,
  type ExrPixelType,
  type EncodeHdrOptions,
  type ImageFileFormat,
  type ImageFileOptions,
  type LinearRgbaImage,
} from '../io/images/index.ts';
export { wavefrontAovChannels, wavefrontAovNames, wavefrontIntegerAovs, isWavefrontAovName, type WavefrontAovName } from './aovs.ts';
export * from './metrics/index.ts';
export * from './adaptive-sampling/index.ts';
export * from './denoise/index.ts';
export { parseDuration, parseAovList } from './option-parsing.ts';
export * from './wavefront-denoise-validation.ts';
