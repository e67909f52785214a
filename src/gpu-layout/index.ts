export {
  rendererWavefrontRecordSizes,
  rendererWavefrontPathStateBytes,
  rendererWavefrontShadowRayBytes,
  rendererWavefrontPrimitiveBytes,
  rendererWavefrontVertexBytes,
  rendererWavefrontInstanceBytes,
  rendererWavefrontBvhNodeBytes,
  rendererWavefrontMaterialBytes,
  rendererWavefrontLightRecordBytes,
  rendererWavefrontAccumulationTexelBytes,
  wavefrontRecordLayouts,
} from './records.ts';
export { rendererWavefrontComputeStatsStride, rendererWavefrontComputeWorkgroupSize, queueCounterSlots, bvhTraversalStackSize } from './constants.ts';
export { pathTracerBindings, bindGroupIndices, type PathTracerBindingName } from './bindings.ts';
export { defineStructLayout, structLayoutToWgsl, writeStruct, readStruct, type StructLayout, type StructFieldLayout, type WgslFieldType } from './struct-layout.ts';
