export { createWavefrontPathTracingComputeRenderer } from './renderer.ts';
export { renderWavefrontPathTracingComputeFrame, type WavefrontOneShotResult } from './one-shot.ts';
export { createWavefrontPathTracingComputeConfig, maxWavefrontDepth, pathTracingIntegrators, wavefrontOptionNames, type WavefrontPathTracingComputeConfig } from './config.ts';
export { createWavefrontPathTracingComputeShaderSource, type WavefrontShaderSources } from './shader-source.ts';
export { createWavefrontMeshAcceleration, createWavefrontGpuMeshSource, packWavefrontSceneObjects, type WavefrontMeshAcceleration } from './scene/public-helpers.ts';
export {
  createWavefrontReferenceRay,
  intersectWavefrontReferenceTriangle,
  traceWavefrontReferenceTriangles,
  type WavefrontReferenceRay,
  type WavefrontReferenceTriangle,
  type WavefrontReferenceHit,
  type WavefrontReferenceTraceResult,
} from './reference.ts';
export { integratorKernels, wavefrontKernels } from './pipelines.ts';
export { defaultDenoiseSettings, outputOptionNames, type WavefrontOutputConfig } from './output-options.ts';
export { featureFlagNames, resolveFeatureFlags, transportExperimentBehaviour, transportExperimentNames } from './feature-flags.ts';
export type * from './types.ts';
export { instancingModes, type InstancingMode } from './scene/instancing.ts';

/** The execution model of the path tracer. */
export const rendererWavefrontComputeMode = 'wavefront-compute' as const;
