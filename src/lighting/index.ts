export { buildAliasTable, aliasTableDistribution, type AliasTable } from './alias-table.ts';
export { buildEmissiveLightTable, type EmissiveLightTable, type EmissiveTriangleInput } from './emissive-lights.ts';
export { validateEnvironmentMap, bilinearTexel, environmentRadiance, MAX_ENVIRONMENT_MAP_DIMENSION, type EnvironmentMap, type EnvironmentMapInput } from './environment-map.ts';
export { directionToEquirectUv, equirectUvToDirection, equirectSinTheta, uvPdfToSolidAngle, solidAnglePdfToUv } from './equirect.ts';
export {
  buildEnvironmentSampler,
  sampleEnvironment,
  environmentPdf,
  filteredTexelLuminance,
  environmentAliasEntryLayout,
  type EnvironmentSampler,
  type EnvironmentSample,
} from './environment-sampling.ts';
export { decodeRadianceHdr, isRadianceHdr, type DecodedHdrImage } from './radiance-hdr.ts';
export { decodeOpenExr, isOpenExr, type ExrLoaderLike, type ExrLoaderConstructor } from './openexr.ts';
export { loadEnvironmentMap, type EnvironmentMapSource, type LoadEnvironmentMapOptions } from './load-environment-map.ts';
