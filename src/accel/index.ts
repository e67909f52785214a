export {
  buildBvh,
  buildBvhAsync,
  buildBvhParallel,
  terminateBvhWorkers,
  warmBvhWorkers,
  BVH_MAX_DEPTH,
  BVH_NODE_BYTES,
  BVH_PARALLEL_MIN_TRIANGLES,
} from './bvh-builder.ts';
export type { BvhBuildResult, BvhBuildOptions, BvhAsyncBuildOptions } from './bvh-builder.ts';
export { computeSahCost, computeThreeMeshBvhSahCost } from './bvh-sah.ts';
export type { SahCostOptions } from './bvh-sah.ts';
export { GpuBvhBuilder, GpuBvhRefitter } from './gpu-build/gpu-bvh-builder.ts';
export type { GpuBvhBuildOptions, GpuBvhBuffers, GpuBvhBuildResult, GpuBvhRefitResult, RefitTarget as GpuBvhRefitTarget } from './gpu-build/gpu-bvh-builder.ts';
export { sortPairsOnGpu } from './gpu-build/radix-sort.ts';
export { packWavefrontTriangles, packWavefrontBvhNodes, packPrimitives, bvhParentLinks } from './triangle-packing.ts';
export type { TriangleMeta } from './triangle-packing.ts';
export {
  traceClosestReference,
  traceAnyReference,
  bruteForceClosest,
  bruteForceAny,
  intersectPackedTriangle,
} from './bvh-reference-traversal.ts';
export type { ReferenceRay, ReferenceHit, ReferenceScene } from './bvh-reference-traversal.ts';
