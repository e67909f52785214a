export { createWavefrontPathTracingComputeRenderer } from './renderer.ts';
export { renderWavefrontPathTracingComputeFrame, type WavefrontOneShotResult } from './one-shot.ts';
export { createWavefrontPathTracingComputeConfig, maxWavefrontDepth, type WavefrontPathTracingComputeConfig } from './config.ts';
export { createWavefrontPathTracingComputeShaderSource, type WavefrontShaderSources } from './shader-source.ts';
export { createWavefrontMeshAcceleration, createWavefrontMeshAccelerationAsync, type WavefrontMeshAcceleration } from './mesh-acceleration.ts';
export {
  createWavefrontReferenceRay,
  intersectWavefrontReferenceTriangle,
  traceWavefrontReferenceTriangles,
  type WavefrontReferenceRay,
  type WavefrontReferenceTriangle,
  type WavefrontReferenceHit,
  type WavefrontReferenceTraceResult,
} from './reference.ts';
export { wavefrontKernels } from './kernels.ts';
export type * from './types.ts';

/** The execution model of the path tracer. */
export const rendererWavefrontComputeMode = 'wavefront-compute' as const;
