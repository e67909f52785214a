export {
  rendererWorkerQueueClass,
  rendererDebugOwner,
  defaultRendererWorkerProfile,
  defaultRendererClearColor,
  type RendererWorkerProfileName,
} from './worker-constants.ts';
export {
  getRendererWorkerProfile,
  getRendererWorkerManifest,
  rendererWorkerProfiles,
  rendererWorkerProfileNames,
  rendererWorkerManifests,
} from './worker-manifests.ts';
export { topologicalJobOrder } from './validate-manifest.ts';
export type {
  RendererWorkerJob,
  RendererWorkerManifest,
  RendererWorkerProfile,
  RendererJobBudgetLevel,
  RendererJobAuthority,
  RendererJobImportance,
} from './worker-manifest-types.ts';
export {
  createRayTracingRenderPlan,
  rayTracingRenderPlanSchemaVersion,
  renderPlanDefaultTileSize,
  renderPlanDefaultMaxDepth,
  renderPlanMaxDepthLimit,
  type RayTracingRenderPlan,
  type RayTracingRenderPlanOptions,
  type RenderPlanStage,
  type RepresentationBand,
  type RecordContract,
} from './render-plan.ts';
