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
export { encodePng, type Rgba8Image } from './png.ts';
export { writePng } from './png-node.ts';
export { wavefrontAovChannels, wavefrontAovNames, wavefrontIntegerAovs, isWavefrontAovName, type WavefrontAovName } from './aovs.ts';
export * from './files/index.ts';
export * from './metrics/index.ts';
export * from './adaptive-sampling/index.ts';
export * from './denoise/index.ts';
export { parseDuration, parseAovList } from './option-parsing.ts';
export * from './wavefront-denoise-validation.ts';
