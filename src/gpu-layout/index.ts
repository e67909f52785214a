export {
  rendererWavefrontComputeStatsStride,
  rendererWavefrontComputeWorkgroupSize,
  rendererWavefrontRecordSizes,
  rendererWavefrontPathStateBytes,
  rendererWavefrontShadowRayBytes,
  rendererWavefrontTriangleBytes,
  rendererWavefrontTriangleAttributesBytes,
  rendererWavefrontBvhNodeBytes,
  rendererWavefrontMaterialBytes,
  rendererWavefrontSceneObjectBytes,
  rendererWavefrontLightEntryBytes,
  rendererWavefrontAccumulationTexelBytes,
  wavefrontRecordLayouts,
  queueCounterSlots,
} from './records.ts';
export { defineStructLayout, structLayoutToWgsl, writeStruct, readStruct, type StructLayout, type StructFieldLayout, type WgslFieldType } from './struct-layout.ts';
