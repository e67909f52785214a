// The film: what happens to the path tracer's samples once they exist. Accumulation and the AOVs,
// adaptive sampling, the denoisers (one interface), display (resolve, present, tone mapping) and
// the image metrics that judge the result.
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
export { wavefrontAovChannels, wavefrontAovNames, wavefrontIntegerAovs, isWavefrontAovName, type WavefrontAovName } from './aovs.ts';
export * from './metrics/index.ts';
export * from './adaptive/index.ts';
export * from './denoise/index.ts';
export { parseDuration, parseAovList } from './option-parsing.ts';
export * from './denoise/validation.ts';
