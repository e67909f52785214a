export { buildAliasTable, aliasTableDistribution, type AliasTable } from './alias-table.ts';
export { luminance } from './emissive-lights.ts';
export { validateEnvironmentMap, bilinearTexel, environmentRadiance, MAX_ENVIRONMENT_MAP_DIMENSION, type EnvironmentMap, type EnvironmentMapInput } from './environment-map.ts';
export { directionToEquirectUv, equirectUvToDirection, equirectSinTheta, uvPdfToSolidAngle, solidAnglePdfToUv } from './equirect.ts';
export {
  buildEnvironmentSampler,
  environmentTableSize,
  sampleEnvironment,
  environmentPdf,
  filteredTexelLuminance,
  environmentAliasEntryLayout,
  type EnvironmentSampler,
  type EnvironmentSample,
} from './environment-sampling.ts';
// The HDR and OpenEXR readers live in src/io/images; re-exported here, where they were first published.
export { decodeRadianceHdr, isRadianceHdr, type DecodedHdrImage } from '../io/images/radiance-hdr.ts';
export { decodeOpenExr, isOpenExr, type DecodeOpenExrOptions, type ExrLoaderLike, type ExrLoaderConstructor } from '../io/images/openexr.ts';
export { loadEnvironmentMap, type EnvironmentMapSource, type LoadEnvironmentMapOptions, type NegativeTexelReport } from './load-environment-map.ts';
export type { WavefrontAreaLightInput, WavefrontRectangleLightInput, WavefrontDiskLightInput, WavefrontSphereLightInput } from './light-types.ts';
export {
  validatePunctualLight,
  punctualLightIncident,
  packPunctualLights,
  punctualLightLayout,
  spotAngleScaleOffset,
  PUNCTUAL_LIGHT_POINT,
  PUNCTUAL_LIGHT_SPOT,
  PUNCTUAL_LIGHT_DIRECTIONAL,
  type PunctualLight,
  type PunctualLightType,
  type PunctualIncident,
} from './punctual-lights.ts';
export {
  validateAreaLight,
  packAreaLights,
  areaLightLayout,
  AREA_LIGHT_RECTANGLE,
  AREA_LIGHT_DISK,
  AREA_LIGHT_SPHERE,
  AREA_LIGHT_FLAG_TWO_SIDED,
  RECTANGLE_ORTHOGONALITY_TOLERANCE,
  type AreaLight,
  type AreaLightType,
} from './area-lights.ts';
export { sampleAreaLight, areaLightPdf, intersectAreaLight, type AreaLightSample, type AreaLightHit } from './area-light-sampling.ts';
export {
  initSphericalRectangle,
  sampleSphericalRectangle,
  MIN_SPHERICAL_RECTANGLE_SOLID_ANGLE,
  MAX_SPHERICAL_RECTANGLE_SOLID_ANGLE,
  type SphericalRectangle,
} from './spherical-rectangle.ts';
export { lightBoundsImportance, unionBounds, unionCones, type LightBounds } from './light-bounds.ts';
export {
  buildLightTree,
  sampleLightTree,
  lightTreePmf,
  packLightTree,
  lightTreeNodeLayout,
  LIGHT_TREE_NONE,
  LIGHT_TREE_FLAG_LEAF,
  LIGHT_TREE_FLAG_TWO_SIDED,
  type LightTree,
  type LightTreeNode,
  type LightTreeItem,
  type LightTreeSample,
} from './light-tree.ts';
export {
  buildLightSampler,
  sampleLight,
  lightPmf,
  triangleLightBounds,
  areaLightBounds,
  punctualLightBounds,
  type LightSampler,
  type LightSamplerInput,
  type LightRef,
  type LightKind,
  type LightSelection,
} from './light-sampler.ts';
export { createHosekWilkieSky, hosekWilkieRadiance, type HosekWilkieSky } from './hosek-wilkie.ts';
export { solarDiscRadiance, relativeAirMass, cieXyzMatching, planckRadiance, xyzToLinearSrgb, LUMENS_PER_WATT, SOLAR_BLACKBODY_KELVIN } from './solar-radiance.ts';
export { sampleSun, sunPdf, sunRadiance, sunSolidAngle, sunLightLayout, oneMinusCos, type SunLight, type SunSample } from './sun-light.ts';
export {
  createNeutralEnvironment,
  neutralEnvironmentRadiance,
  neutralEnvironmentMeanRadiance,
  NEUTRAL_SOFTBOXES,
  NEUTRAL_DOME_HORIZON,
  NEUTRAL_DOME_GRADIENT,
  NEUTRAL_FLOOR,
  type NeutralEnvironmentOptions,
} from './neutral-environment.ts';
export { sceneLightSources, type SceneWithLighting } from './scene-light-sources.ts';
export { cieOvercastRadiance, studioRadiance, STUDIO_SOFTBOXES, CIE_OVERCAST_ILLUMINANCE_FACTOR, type StudioSoftbox } from './procedural-skies.ts';
export {
  createEnvironmentLighting,
  validateEnvironmentLighting,
  clearSkyRadiance,
  type EnvironmentLighting,
  type EnvironmentLightingInput,
  type EnvironmentLightingPreset,
} from './environment-lighting.ts';
export {
  validateEnvironmentPortals,
  validateEnvironmentPortalMode,
  buildPortalEnvironmentSampler,
  samplePortalEnvironment,
  portalEnvironmentPdf,
  portalUvToDirection,
  portalDirectionToUv,
  portalWindow,
  buildWindowedDistribution,
  sampleWindowed,
  windowedPdf,
  windowIntegral,
  packPortals,
  environmentPortalLayout,
  PORTAL_GUIDE_PROBABILITY,
  PORTAL_DENSITY_FLOOR,
  type EnvironmentPortalInput,
  type EnvironmentPortalMode,
  type Portal,
  type PortalEnvironmentSampler,
  type PortalEnvironmentSample,
  type WindowedDistribution,
} from './portals.ts';
export { validateLights, type ValidatedLights } from './lights.ts';
export { packEnvironment, environmentMapUniformsLayout, type PackedEnvironment } from './environment-tables.ts';
export {
  validateLightingOptions,
  AUTO_LIGHT_TREE_THRESHOLD,
  type WavefrontLightingOptions,
  type WavefrontSceneLightInput,
  type WavefrontLightSamplerMode,
  type LightingConfig,
  type LightingEnvironment,
} from './lighting-options.ts';
export {
  buildGpuLighting,
  lightGroupProbabilities,
  MAX_ENVIRONMENT_TABLE_CELLS,
  MIN_GROUP_PROBABILITY,
  type GpuLighting,
  type GpuLightingInput,
  type LightGroupProbabilities,
} from './gpu-lighting.ts';
export { uploadEnvironmentTexture, type UploadedEnvironment } from './upload-environment.ts';
