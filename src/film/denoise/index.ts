export { denoiseAtrousReference, demodulationMinAlbedo, unknownVariance, type AtrousDenoiseInput, type AtrousDenoiseSettings } from './atrous-reference.ts';
export type { DenoiserDispatchTally, WavefrontDenoiser, WavefrontDenoiserEntry, WavefrontDenoiserFactory, WavefrontDenoiserName, WavefrontDenoiserTarget } from './denoiser.ts';
export {
  OidnNetwork,
  OidnImageDenoiser,
  compileOidnPipelines,
  defaultOidnMaxMemoryBytes,
  oidnPrecisionFor,
  type OidnBufferAllocator,
  type OidnImageOptions,
  type OidnImageSource,
  type OidnPipelines,
} from './oidn/oidn-network.ts';
export { denoiseOidnReference, type OidnReferenceInput } from './oidn/oidn-reference.ts';
export { loadOidnModel, oidnModelFromBytes, type OidnBuiltinWeights } from './oidn/weights.ts';
export { parseTza, type TzaTensor } from './oidn/tza.ts';
export { unetFromTensors, unetAlignment, unetReceptiveField, type UNetConv, type UNetModel } from './oidn/unet.ts';
export type { OidnPrecision, TilePlan, OidnTile } from './oidn/packing.ts';
