// The public API of @plasius/gpu-renderer, by name: what the README documents (the renderers, their
// options and statistics types, loaders, scene helpers, errors, output and file helpers, sequences,
// the runtime, planning, XR) and the names of the API it stays compatible with. Every other module
// is internal: tests, benchmarks and scripts reach it through src/internal.ts, which the package does
// not publish. test/api/public-api.test.ts lists these names; adding or removing one is an API
// change that must update that list (and the README) too.

// Typed errors (GpuRendererError and its codes).
export {
  GpuRendererError, isGpuRendererError, type GpuRendererErrorCode,
} from './errors/index.ts';

// WebGPU availability and devices.
export {
  acquireGpuDevice, supportsWebGpu, type AcquiredGpuDevice, type AcquireGpuDeviceOptions,
  type SupportsWebGpuOptions,
} from './gpu/index.ts';

// GPU record sizes: the renderer's public compute limits.
export {
  rendererWavefrontAccumulationTexelBytes, rendererWavefrontBvhNodeBytes,
  rendererWavefrontComputeStatsStride, rendererWavefrontComputeWorkgroupSize, rendererWavefrontInstanceBytes,
  rendererWavefrontLightRecordBytes, rendererWavefrontMaterialBytes, rendererWavefrontPathStateBytes,
  rendererWavefrontPrimitiveBytes, rendererWavefrontRecordSizes, rendererWavefrontShadowRayBytes,
  rendererWavefrontVertexBytes, type StructFieldLayout, type StructLayout, type WgslFieldType,
} from './gpu-layout/index.ts';

// The scene description: inputs, validation, the scene JSON format, camera framing.
export {
  createCornellBoxScene, frameBounds, lookAtCamera, maxCoordinateMagnitude, maxEmittedPower, maxRadiance,
  normalizeMaterial, normalizeWavefrontInstance, normalizeWavefrontMesh, normalizeWavefrontScene,
  normalizeWavefrontSceneObject, orbitCamera, parseSceneFile, sceneBounds, validateSceneDescription,
  type FrameBoundsOptions, type GltfSceneReference, type NormalizedInstance, type NormalizedMaterial,
  type NormalizedMesh, type NormalizedScene, type NormalizedSceneObject, type NormalizedTextureRef,
  type SceneBounds, type Vec2Input, type Vec3Input, type Vec4Input, type WavefrontAlphaMode,
  type WavefrontCameraInput, type WavefrontEnvironmentInput, type WavefrontEnvironmentMapReference,
  type WavefrontImageInput, type WavefrontImageLevel, type WavefrontInstanceInput, type WavefrontLightInput, type WavefrontMagFilter,
  type WavefrontMaterialInput, type WavefrontMeshInput, type WavefrontMinFilter,
  type WavefrontPunctualLightInput, type WavefrontSamplerInput, type WavefrontSceneDescription,
  type WavefrontSceneFile, type WavefrontSceneObjectInput, type WavefrontTextureInput,
  type WavefrontTextureRefInput, type WavefrontTextureTransformInput, type WavefrontToneMapping,
  type WavefrontWrapMode,
} from './scene/index.ts';

// BVH builds (CPU, workers, GPU) and their reference traversal.
export {
  bruteForceClosest, buildBvh, buildBvhAsync, buildBvhParallel, computeSahCost, GpuBvhBuilder,
  GpuBvhRefitter, packWavefrontBvhNodes, packWavefrontTriangles, sortPairsOnGpu, terminateBvhWorkers,
  traceClosestReference, warmBvhWorkers, type BvhAsyncBuildOptions, type BvhBuildOptions,
  type BvhBuildResult, type GpuBvhBuffers, type GpuBvhBuildOptions, type GpuBvhBuildResult,
  type GpuBvhRefitResult, type GpuBvhRefitTarget, type ReferenceHit, type ReferenceRay, type ReferenceScene,
  type SahCostOptions, type TriangleMeta,
} from './accel/index.ts';

// Lights and environments, with the CPU references the GPU is tested against.
export {
  areaLightPdf, buildAliasTable, buildEnvironmentSampler, buildLightTree, buildPortalEnvironmentSampler,
  createEnvironmentLighting, createNeutralEnvironment, environmentPdf, lightTreePmf, neutralEnvironmentMeanRadiance, loadEnvironmentMap, luminance,
  portalEnvironmentPdf, punctualLightIncident, sampleAreaLight, sampleEnvironment, sampleLightTree,
  samplePortalEnvironment, validateEnvironmentMap, type AliasTable, type AreaLight, type AreaLightSample,
  type AreaLightType, type EnvironmentLighting, type EnvironmentLightingInput,
  type EnvironmentLightingPreset, type EnvironmentMap, type EnvironmentMapInput, type EnvironmentMapSource,
  type EnvironmentPortalInput, type EnvironmentPortalMode, type EnvironmentSample, type EnvironmentSampler,
  type ExrLoaderConstructor, type ExrLoaderLike, type LightBounds, type LightingConfig,
  type LightingEnvironment, type LightTree, type LightTreeItem, type LightTreeNode, type LightTreeSample,
  type LoadEnvironmentMapOptions, type NegativeTexelReport, type NeutralEnvironmentOptions, type Portal, type PortalEnvironmentSample,
  type PortalEnvironmentSampler, type PunctualIncident, type PunctualLight, type PunctualLightType,
  type SunLight, type WavefrontAreaLightInput, type WavefrontDiskLightInput, type WavefrontLightingOptions,
  type WavefrontLightSamplerMode, type WavefrontRectangleLightInput, type WavefrontSceneLightInput,
  type WavefrontSphereLightInput, type WindowedDistribution,
} from './lighting/index.ts';

// The wavefront path tracer, its options, statistics and reference helpers.
export {
  createWavefrontGpuMeshSource, createWavefrontMeshAcceleration, createWavefrontPathTracingComputeConfig,
  createWavefrontPathTracingComputeRenderer, createWavefrontPathTracingComputeShaderSource,
  createWavefrontReferenceRay, featureFlagNames, intersectWavefrontReferenceTriangle, maxWavefrontDepth,
  packWavefrontSceneObjects, pathTracingIntegrators, rendererWavefrontComputeMode, renderWavefrontPathTracingComputeFrame,
  traceWavefrontReferenceTriangles, transportExperimentNames, instancingModes, type InstancingMode, type WavefrontInstancingStats, type AccelerationBuildMode, type BvhUpdateMode,
  type CanvasTarget, type PathTracingIntegrator, type TransportExperimentName, type WavefrontAdaptiveFrameStats,
  type WavefrontAdaptiveSettings, type WavefrontDenoiseOptions, type WavefrontDenoiseSettings,
  type WavefrontFeatureFlagResolution, type WavefrontFeatureFlagState, type WavefrontFrameStats,
  type WavefrontGeometryUpdate, type WavefrontGeometryUpdateStats, type WavefrontGpuParallelism,
  type WavefrontInstanceTransformUpdate, type WavefrontMemoryStats, type WavefrontMeshAcceleration,
  type WavefrontMeshGeometryUpdate, type WavefrontOneShotResult, type WavefrontOutputConfig,
  type WavefrontOutputOptions, type WavefrontOutputState, type WavefrontPathTracingComputeConfig,
  type WavefrontPathTracingOptions, type WavefrontPathTracingRenderer, type WavefrontPixelImage,
  type WavefrontPresentationOutput, type WavefrontProgressListener, type WavefrontRadianceDiagnostics,
  type WavefrontRadianceImage, type WavefrontRayCounts, type WavefrontReferenceHit,
  type WavefrontReferenceRay, type WavefrontReferenceTraceResult, type WavefrontReferenceTriangle,
  type WavefrontRendererSnapshot, type WavefrontRenderFrameOptions, type WavefrontRenderProgress,
  type WavefrontSceneUpdate, type WavefrontShaderSources, type WavefrontTerminalRadiance,
  type WavefrontTransportExperimentState, type WavefrontTransportGuardrails,
} from './pathtracer/index.ts';

// Output: the film's tone mapping, adaptive sampling, denoisers, image metrics.
export {
  adaptiveConvergedMask, adaptiveSamplingError, applyToneMapping, createWavefrontAdaptiveSamplingLevels,
  denoiseAtrousReference, denoiseOidnReference, displayPeakSignalToNoiseRatio, displayStructuralSimilarity,
  encodeRadianceToRgba8, linearToSrgb, loadOidnModel, meanSquaredError, OidnNetwork, parseAovList,
  parseDuration, peakSignalToNoiseRatio, relativeMeanSquaredError, rootMeanSquaredError, srgbToLinear,
  structuralSimilarity, toneMapAces, toneMapAgx, toneMapPbrNeutral, toneMappingNames,
  validateWavefrontDenoise, wavefrontAovNames, type AdaptiveConvergenceOptions,
  type AdaptiveConvergenceResult, type AtrousDenoiseInput, type AtrousDenoiseSettings,
  type DenoiserDispatchTally, type DenoiseValidationCriterion, type DenoiseValidationInput,
  type DenoiseValidationRegion, type DenoiseValidationReport, type DenoiseValidationThresholds,
  type EncodeRadianceOptions, type GrayImage, type OidnBufferAllocator, type OidnBuiltinWeights,
  type OidnImageOptions, type OidnImageSource, type OidnPipelines, type OidnPrecision,
  type OidnReferenceInput, type Rgb, type SsimOptions, type ToneMappingMode, type UNetConv, type UNetModel,
  type WavefrontAdaptiveSamplingLevel, type WavefrontAdaptiveSamplingLevelConfig,
  type WavefrontAdaptiveSamplingLevelOptions, type WavefrontAovName, type WavefrontDenoiser,
  type WavefrontDenoiserName,
} from './film/index.ts';

// Image files in both directions.
export {
  decodeHdr, encodeExr, encodeHdr, encodeImageFile, encodePng, writeImageFile, writePng,
  type EncodeExrOptions, type EncodeHdrOptions, type ExrCompression, type ExrLayer, type ExrPixelType,
  type ImageFileFormat, type ImageFileOptions, type LinearRgbaImage, type Rgba8Image,
} from './io/index.ts';

// The general frame-loop runtime.
export {
  createGpuRenderer, createRendererDebugHooks, type GpuRenderer, type GpuRendererCanvas,
  type GpuRendererDeviceState, type GpuRendererFormat, type GpuRendererOptions, type GpuRendererSize,
  type GpuRendererSnapshot, type RendererClearColorInput, type RendererDebugFrameSample,
  type RendererDebugHookOptions, type RendererDebugHooks, type RendererDebugSession,
  type RendererDeviceLostInfo, type RendererEncodeContext, type RendererFrameIdInput, type RendererFrameInfo,
  type RendererFrameResult, type RendererFrameTimeGovernor, type RendererPixels, type RendererRgba,
} from './runtime/index.ts';

// Render plans and worker manifests.
export {
  createRayTracingRenderPlan, defaultRendererClearColor, defaultRendererWorkerProfile,
  getRendererWorkerManifest, getRendererWorkerProfile, rendererDebugOwner, rendererWorkerManifests,
  rendererWorkerProfileNames, rendererWorkerProfiles, rendererWorkerQueueClass, type RayTracingRenderPlan,
  type RayTracingRenderPlanOptions, type RecordContract, type RendererJobAuthority,
  type RendererJobBudgetLevel, type RendererJobImportance, type RendererWorkerJob,
  type RendererWorkerManifest, type RendererWorkerProfile, type RendererWorkerProfileName,
  type RenderPlanStage, type RepresentationBand,
} from './planning/index.ts';

// Transport helpers: media, Fresnel interfaces, spectral samples.
export {
  beerLambertTransmittance, createMediumStack, createSpectralSamples, createTransportBranches,
  dielectricInterface, dispersiveIor, fresnelDielectric, type DielectricInterface, type MediumStack,
  type MediumStackTransition, type SpectralSample, type SpectralSampleOptions, type TransportBranch,
  type TransportBranches, type TransportBranchOptions,
} from './transport/index.ts';

// WebXR binding.
export {
  bindRendererToXrManager, type XrBindableRenderer, type XrBindingOptions, type XrManagerLike,
  type XrManagerState, type XrSessionEvent,
} from './xr/index.ts';

// glTF animation: clips, poses, skinning, camera rigs, timelines.
export {
  skinVertices, type AnimatedCameraOptionsInput, type AnimatedSceneCoreOptions, type AnimationBeatInput,
  type AnimationSnapshotCore, type CameraConstraintsInput, type CameraTransform, type CameraViewMode,
  type ClipAssetInput, type ClipMovementProfileInput, type HeadLookIntent, type ModelMorphTarget,
  type ModelPrimitive, type MorphedStreams, type MovementDiagnostic, type MovementDiagnosticCode,
  type MovementKind, type MovementRequirementInput, type MovementTolerances, type MovementValidation,
  type PropGroundAnchor, type PropInput, type RoutePointInput, type SkinnedStreams, type TerrainHeight,
} from './animation/index.ts';

// Asset loading (glTF, scene files) and the resource policy that bounds it.
export {
  defaultResourcePolicy, loadGltfScene, loadSceneFile, resolveResourcePolicy, resolveSceneFile,
  type GltfAnimationInfo, type GltfBounds, type GltfCameraInfo, type GltfDecoderModules,
  type GltfLoadOptions, type GltfPoseAgainOptions, type GltfPoseOptions, type GltfScene, type GltfSource,
  type ResolvedResourcePolicy, type ResolvedSceneFile, type ResolveSceneFileOptions, type ResourcePolicy,
  type WavefrontResolvedScene,
} from './io/index.ts';

// The raster renderer and the animated scenes.
export {
  createAnimatedSceneRenderer, createProfessionalAnimatedSceneRenderer, createRasterRenderer,
  type AnimatedPosedScene, type AnimatedSceneRenderer, type AnimatedSceneRendererOptions,
  type AnimatedSceneSnapshot, type RasterFrameStats, type RasterRenderer, type RasterRendererOptions,
  type RasterShadowOptions, type RasterSkinnedInstanceInput, type RasterSkinnedMeshInput,
} from './raster/index.ts';

// Image sequences and turntables.
export {
  createSequenceRenderer, gltfSequence, outputPaths, parseFrameList, planGltfSequence, poseGltfSequenceItem,
  turntableCamera, writeFrameFile, type GltfSequenceFrame, type GltfSequenceItem, type GltfSequenceOptions,
  type OutputPatternValues, type SequenceRenderer, type SequenceRendererOptions,
  type SequenceRendererSettings, type TurntableOptions,
} from './sequence/index.ts';
