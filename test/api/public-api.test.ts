// The package root's API, name by name. The lists below are the reviewed public API: a name added
// to or removed from src/index.ts fails this test until the list (and the README) says so. The
// names come from the TypeScript compiler (values and types apart), the runtime module, and the
// built ESM and CommonJS entries, which must all agree.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import ts from 'typescript';
import * as pkg from '../../src/index.ts';
import * as internal from '../../src/internal.ts';
import { builtPackageDir } from '../browser/built-package.ts';

const root = fileURLToPath(new URL('../..', import.meta.url));

/** Runtime exports: functions, classes and constants. */
const publicValues = [
  'acquireGpuDevice', 'adaptiveConvergedMask', 'adaptiveSamplingError', 'applyToneMapping', 'areaLightPdf',
  'beerLambertTransmittance', 'bindRendererToXrManager', 'bruteForceClosest', 'buildAliasTable', 'buildBvh',
  'buildBvhAsync', 'buildBvhParallel', 'buildEnvironmentSampler', 'buildLightTree',
  'buildPortalEnvironmentSampler', 'computeSahCost', 'createAnimatedSceneRenderer', 'createCornellBoxScene',
  'createEnvironmentLighting', 'createGpuRenderer', 'createMediumStack', 'createNeutralEnvironment',
  'createProfessionalAnimatedSceneRenderer', 'createRasterRenderer', 'createRayTracingRenderPlan',
  'createRendererDebugHooks', 'createSequenceRenderer', 'createSpectralSamples', 'createTransportBranches',
  'createWavefrontAdaptiveSamplingLevels', 'createWavefrontGpuMeshSource', 'createWavefrontMeshAcceleration',
  'createWavefrontPathTracingComputeConfig', 'createWavefrontPathTracingComputeRenderer',
  'createWavefrontPathTracingComputeShaderSource', 'createWavefrontReferenceRay', 'decodeHdr',
  'defaultRendererClearColor', 'defaultRendererWorkerProfile', 'defaultResourcePolicy',
  'denoiseAtrousReference', 'denoiseOidnReference', 'dielectricInterface', 'dispersiveIor',
  'displayPeakSignalToNoiseRatio', 'displayStructuralSimilarity', 'encodeExr', 'encodeHdr', 'encodeImageFile',
  'encodePng', 'encodeRadianceToRgba8', 'environmentPdf', 'featureFlagNames', 'frameBounds',
  'fresnelDielectric', 'getRendererWorkerManifest', 'getRendererWorkerProfile', 'gltfSequence',
  'GpuBvhBuilder', 'GpuBvhRefitter', 'GpuRendererError', 'instancingModes', 'intersectWavefrontReferenceTriangle',
  'isGpuRendererError', 'lightTreePmf', 'linearToSrgb', 'loadEnvironmentMap', 'loadGltfScene',
  'loadOidnModel', 'loadSceneFile', 'lookAtCamera', 'luminance', 'maxCoordinateMagnitude', 'maxEmittedPower',
  'maxRadiance', 'maxWavefrontDepth', 'meanSquaredError', 'neutralEnvironmentMeanRadiance', 'normalizeMaterial', 'normalizeWavefrontInstance',
  'normalizeWavefrontMesh', 'normalizeWavefrontScene', 'normalizeWavefrontSceneObject', 'OidnNetwork',
  'orbitCamera', 'outputPaths', 'packWavefrontBvhNodes', 'packWavefrontSceneObjects',
  'packWavefrontTriangles', 'parseAovList', 'pathTracingIntegrators', 'parseDuration', 'parseFrameList', 'parseSceneFile',
  'peakSignalToNoiseRatio', 'planGltfSequence', 'portalEnvironmentPdf', 'poseGltfSequenceItem',
  'punctualLightIncident', 'relativeMeanSquaredError', 'rendererDebugOwner',
  'rendererWavefrontAccumulationTexelBytes', 'rendererWavefrontBvhNodeBytes', 'rendererWavefrontComputeMode',
  'rendererWavefrontComputeStatsStride', 'rendererWavefrontComputeWorkgroupSize',
  'rendererWavefrontInstanceBytes', 'rendererWavefrontLightRecordBytes', 'rendererWavefrontMaterialBytes',
  'rendererWavefrontPathStateBytes', 'rendererWavefrontPrimitiveBytes', 'rendererWavefrontRecordSizes',
  'rendererWavefrontShadowRayBytes', 'rendererWavefrontVertexBytes', 'rendererWorkerManifests',
  'rendererWorkerProfileNames', 'rendererWorkerProfiles', 'rendererWorkerQueueClass',
  'renderWavefrontPathTracingComputeFrame', 'resolveResourcePolicy', 'resolveSceneFile',
  'rootMeanSquaredError', 'sampleAreaLight', 'sampleEnvironment', 'sampleLightTree',
  'samplePortalEnvironment', 'sceneBounds', 'skinVertices', 'sortPairsOnGpu', 'srgbToLinear',
  'structuralSimilarity', 'supportsWebGpu', 'terminateBvhWorkers', 'toneMapAces', 'toneMapAgx',
  'toneMapPbrNeutral', 'toneMappingNames', 'traceClosestReference', 'traceWavefrontReferenceTriangles',
  'transportExperimentNames', 'turntableCamera', 'validateEnvironmentMap', 'validateSceneDescription',
  'validateWavefrontDenoise', 'warmBvhWorkers', 'wavefrontAovNames', 'writeFrameFile', 'writeImageFile',
  'writePng',
];

/** Type-only exports: the options, results and inputs of the values above. */
const publicTypes = [
  'AccelerationBuildMode', 'AcquiredGpuDevice', 'AcquireGpuDeviceOptions', 'AdaptiveConvergenceOptions',
  'AdaptiveConvergenceResult', 'AliasTable', 'AnimatedCameraOptionsInput', 'AnimatedPosedScene',
  'AnimatedSceneCoreOptions', 'AnimatedSceneRenderer', 'AnimatedSceneRendererOptions',
  'AnimatedSceneSnapshot', 'AnimationBeatInput', 'AnimationSnapshotCore', 'AreaLight', 'AreaLightSample',
  'AreaLightType', 'AtrousDenoiseInput', 'AtrousDenoiseSettings', 'BvhAsyncBuildOptions', 'BvhBuildOptions',
  'BvhBuildResult', 'BvhUpdateMode', 'InstancingMode', 'CameraConstraintsInput', 'CameraTransform', 'CameraViewMode',
  'CanvasTarget', 'ClipAssetInput', 'ClipMovementProfileInput', 'DenoiserDispatchTally',
  'DenoiseValidationCriterion', 'DenoiseValidationInput', 'DenoiseValidationRegion',
  'DenoiseValidationReport', 'DenoiseValidationThresholds', 'DielectricInterface', 'EncodeExrOptions',
  'EncodeHdrOptions', 'EncodeRadianceOptions', 'EnvironmentLighting', 'EnvironmentLightingInput',
  'EnvironmentLightingPreset', 'EnvironmentMap', 'EnvironmentMapInput', 'EnvironmentMapSource',
  'EnvironmentPortalInput', 'EnvironmentPortalMode', 'EnvironmentSample', 'EnvironmentSampler',
  'ExrCompression', 'ExrLayer', 'ExrLoaderConstructor', 'ExrLoaderLike', 'ExrPixelType', 'FrameBoundsOptions',
  'GltfAnimationInfo', 'GltfBounds', 'GltfCameraInfo', 'GltfDecoderModules', 'GltfLoadOptions',
  'GltfPoseAgainOptions', 'GltfPoseOptions', 'GltfScene', 'GltfSceneReference', 'GltfSequenceFrame',
  'GltfSequenceItem', 'GltfSequenceOptions', 'GltfSource', 'GpuBvhBuffers', 'GpuBvhBuildOptions',
  'GpuBvhBuildResult', 'GpuBvhRefitResult', 'GpuBvhRefitTarget', 'GpuRenderer', 'GpuRendererCanvas',
  'GpuRendererDeviceState', 'GpuRendererErrorCode', 'GpuRendererFormat', 'GpuRendererOptions',
  'GpuRendererSize', 'GpuRendererSnapshot', 'GrayImage', 'HeadLookIntent', 'ImageFileFormat',
  'ImageFileOptions', 'LightBounds', 'LightingConfig', 'LightingEnvironment', 'LightTree', 'LightTreeItem',
  'LightTreeNode', 'LightTreeSample', 'LinearRgbaImage', 'LoadEnvironmentMapOptions', 'MediumStack',
  'MediumStackTransition', 'ModelMorphTarget', 'ModelPrimitive', 'MorphedStreams', 'MovementDiagnostic',
  'MovementDiagnosticCode', 'MovementKind', 'MovementRequirementInput', 'MovementTolerances',
  'MovementValidation', 'NegativeTexelReport', 'NeutralEnvironmentOptions', 'NormalizedInstance', 'NormalizedMaterial', 'NormalizedMesh',
  'NormalizedScene', 'NormalizedSceneObject', 'NormalizedTextureRef', 'OidnBufferAllocator',
  'OidnBuiltinWeights', 'OidnImageOptions', 'OidnImageSource', 'OidnPipelines', 'OidnPrecision',
  'OidnReferenceInput', 'OutputPatternValues', 'PathTracingIntegrator', 'Portal', 'PortalEnvironmentSample',
  'PortalEnvironmentSampler', 'PropGroundAnchor', 'PropInput', 'PunctualIncident', 'PunctualLight',
  'PunctualLightType', 'RasterFrameStats', 'RasterRenderer', 'RasterRendererOptions', 'RasterShadowOptions',
  'RasterSkinnedInstanceInput', 'RasterSkinnedMeshInput', 'RayTracingRenderPlan',
  'RayTracingRenderPlanOptions', 'RecordContract', 'ReferenceHit', 'ReferenceRay', 'ReferenceScene',
  'RendererClearColorInput', 'RendererDebugFrameSample', 'RendererDebugHookOptions', 'RendererDebugHooks',
  'RendererDebugSession', 'RendererDeviceLostInfo', 'RendererEncodeContext', 'RendererFrameIdInput',
  'RendererFrameInfo', 'RendererFrameResult', 'RendererFrameTimeGovernor', 'RendererJobAuthority',
  'RendererJobBudgetLevel', 'RendererJobImportance', 'RendererPixels', 'RendererRgba', 'RendererWorkerJob',
  'RendererWorkerManifest', 'RendererWorkerProfile', 'RendererWorkerProfileName', 'RenderPlanStage',
  'RepresentationBand', 'ResolvedResourcePolicy', 'ResolvedSceneFile', 'ResolveSceneFileOptions',
  'ResourcePolicy', 'Rgb', 'Rgba8Image', 'RoutePointInput', 'SahCostOptions', 'SceneBounds',
  'SequenceRenderer', 'SequenceRendererOptions', 'SequenceRendererSettings', 'SkinnedStreams',
  'SpectralSample', 'SpectralSampleOptions', 'SsimOptions', 'StructFieldLayout', 'StructLayout', 'SunLight',
  'SupportsWebGpuOptions', 'TerrainHeight', 'ToneMappingMode', 'TransportBranch', 'TransportBranches',
  'TransportBranchOptions', 'TransportExperimentName', 'TriangleMeta', 'TurntableOptions', 'UNetConv',
  'UNetModel', 'Vec2Input', 'Vec3Input', 'Vec4Input', 'WavefrontAdaptiveFrameStats',
  'WavefrontAdaptiveSamplingLevel', 'WavefrontAdaptiveSamplingLevelConfig',
  'WavefrontAdaptiveSamplingLevelOptions', 'WavefrontAdaptiveSettings', 'WavefrontAlphaMode',
  'WavefrontAovName', 'WavefrontAreaLightInput', 'WavefrontCameraInput', 'WavefrontDenoiseOptions',
  'WavefrontDenoiser', 'WavefrontDenoiserName', 'WavefrontDenoiseSettings', 'WavefrontDiskLightInput',
  'WavefrontEnvironmentInput', 'WavefrontEnvironmentMapReference', 'WavefrontFeatureFlagResolution',
  'WavefrontFeatureFlagState', 'WavefrontFrameStats', 'WavefrontGeometryUpdate',
  'WavefrontGeometryUpdateStats', 'WavefrontGpuParallelism', 'WavefrontImageInput', 'WavefrontImageLevel', 'WavefrontInstanceInput', 'WavefrontInstancingStats',
  'WavefrontInstanceTransformUpdate', 'WavefrontLightingOptions', 'WavefrontLightInput',
  'WavefrontLightSamplerMode', 'WavefrontMagFilter', 'WavefrontMaterialInput', 'WavefrontMemoryStats',
  'WavefrontMeshAcceleration', 'WavefrontMeshGeometryUpdate', 'WavefrontMeshInput', 'WavefrontMinFilter',
  'WavefrontOneShotResult', 'WavefrontOutputConfig', 'WavefrontOutputOptions', 'WavefrontOutputState',
  'WavefrontPathTracingComputeConfig', 'WavefrontPathTracingOptions', 'WavefrontPathTracingRenderer',
  'WavefrontPixelImage', 'WavefrontPresentationOutput', 'WavefrontProgressListener',
  'WavefrontPunctualLightInput', 'WavefrontRadianceDiagnostics', 'WavefrontRadianceImage',
  'WavefrontRayCounts', 'WavefrontRectangleLightInput', 'WavefrontReferenceHit', 'WavefrontReferenceRay',
  'WavefrontReferenceTraceResult', 'WavefrontReferenceTriangle', 'WavefrontRendererSnapshot',
  'WavefrontRenderFrameOptions', 'WavefrontRenderProgress', 'WavefrontResolvedScene', 'WavefrontSamplerInput',
  'WavefrontSceneDescription', 'WavefrontSceneFile', 'WavefrontSceneLightInput', 'WavefrontSceneObjectInput',
  'WavefrontSceneUpdate', 'WavefrontShaderSources', 'WavefrontSphereLightInput', 'WavefrontTerminalRadiance',
  'WavefrontTextureInput', 'WavefrontTextureRefInput', 'WavefrontTextureTransformInput',
  'WavefrontToneMapping', 'WavefrontTransportExperimentState', 'WavefrontTransportGuardrails',
  'WavefrontWrapMode', 'WgslFieldType', 'WindowedDistribution', 'XrBindableRenderer', 'XrBindingOptions',
  'XrManagerLike', 'XrManagerState', 'XrSessionEvent',
];

/** Classes: constructed through a static `create` (they need a device), except the error. */
const publicClasses = ['GpuBvhBuilder', 'GpuBvhRefitter', 'GpuRendererError', 'OidnNetwork'];

interface CompilerView {
  values: string[];
  types: string[];
  /** Values whose type has call signatures (functions, and constants holding one). */
  callable: string[];
  classes: string[];
}

let view: CompilerView | undefined;

/** The root's exports as the TypeScript compiler sees them (computed once: a full type check). */
function compilerView(): CompilerView {
  view ??= readCompilerView();
  return view;
}

function readCompilerView(): CompilerView {
  const entry = join(root, 'src/index.ts');
  const program = ts.createProgram([entry], { allowImportingTsExtensions: true, module: ts.ModuleKind.NodeNext, moduleResolution: ts.ModuleResolutionKind.NodeNext, noEmit: true, types: [], skipLibCheck: true });
  const checker = program.getTypeChecker();
  const view: CompilerView = { values: [], types: [], callable: [], classes: [] };
  for (const symbol of checker.getExportsOfModule(checker.getSymbolAtLocation(program.getSourceFile(entry)!)!)) {
    const target = symbol.flags & ts.SymbolFlags.Alias ? checker.getAliasedSymbol(symbol) : symbol;
    if (!(target.flags & ts.SymbolFlags.Value)) {
      view.types.push(symbol.name);
      continue;
    }
    view.values.push(symbol.name);
    if (target.flags & ts.SymbolFlags.Class) view.classes.push(symbol.name);
    else if (checker.getTypeOfSymbol(target).getCallSignatures().length > 0) view.callable.push(symbol.name);
  }
  return view;
}

const sorted = (names: Iterable<string>): string[] => [...names].sort((a, b) => a.localeCompare(b, 'en'));

test('public API: the root exports exactly the reviewed values and types', () => {
  const view = compilerView();
  assert.deepEqual(sorted(view.values), sorted(publicValues), 'values (update publicValues and the README when the API changes)');
  assert.deepEqual(sorted(view.types), sorted(publicTypes), 'types (update publicTypes and the README when the API changes)');
  assert.deepEqual(sorted(Object.keys(pkg)), sorted(publicValues), 'the runtime module exports the same values');
  assert.deepEqual(sorted(view.classes), sorted(publicClasses));
});

test('public API: functions are functions, classes construct, constants are data', () => {
  const view = compilerView();
  const exports = pkg as unknown as Record<string, unknown>;
  for (const name of [...view.callable, ...view.classes]) assert.equal(typeof exports[name], 'function', `${name} is callable`);
  for (const name of view.values.filter((n) => !view.callable.includes(n) && !view.classes.includes(n))) {
    assert.notEqual(typeof exports[name], 'function', `${name} is a constant`);
    assert.notEqual(exports[name], undefined, `${name} has a value`);
  }
  const error = new pkg.GpuRendererError('INVALID_OPTION', 'bad width', { field: 'width' });
  assert.ok(error instanceof Error && pkg.isGpuRendererError(error) && error.code === 'INVALID_OPTION' && error.field === 'width');
  for (const name of ['GpuBvhBuilder', 'GpuBvhRefitter', 'OidnNetwork'] as const) assert.equal(typeof pkg[name].create, 'function', `${name}.create(device, ...)`);
});

test('public API: the compatible API answers as its README shows', () => {
  assert.deepEqual(pkg.getRendererWorkerManifest().jobs.map((job) => job.key), ['acquire', 'visibility', 'mainEncode', 'postProcess', 'submit']);
  assert.ok(pkg.getRendererWorkerManifest('xr').jobs.some((job) => job.key === 'lateLatch'));
  const plan = pkg.createRayTracingRenderPlan({ snapshotId: 'visual-snapshot-42' });
  assert.ok(plan.renderStages.length > 0 && plan.inputBoundary !== undefined && plan.wavefront.queueLayout.strategy !== undefined);
  const stack = pkg.createMediumStack([1, 4]);
  const branches = pkg.createTransportBranches({ mediumStack: stack, mediumId: 7, transmission: 1, ior: 1.5 });
  assert.ok(branches.reflected.weight + (branches.transmitted?.weight ?? 0) > 0.99);
  assert.ok(pkg.createSpectralSamples({ ior: 1.5, dispersion: 0.2 }).length > 1);
});

test('public API: every public name is also in the internal entry, the same binding', () => {
  const all = internal as unknown as Record<string, unknown>;
  for (const name of publicValues) assert.equal(all[name], (pkg as unknown as Record<string, unknown>)[name], name);
});

test('public API: the built ESM and CommonJS entries export the same names as the source', { timeout: 300_000 }, async (t) => {
  const esm = builtPackageDir(root);
  t.after(() => esm.cleanup());
  const esmNames = Object.keys(await import(pathToFileURL(join(esm.dir, 'index.js')).href));
  assert.deepEqual(sorted(esmNames), sorted(publicValues), 'dist/esm');

  // The CommonJS build, compiled fresh (as scripts/build.ts does) so a stale dist never answers.
  const cache = join(root, 'node_modules/.cache');
  mkdirSync(cache, { recursive: true });
  const out = mkdtempSync(join(cache, 'gpu-renderer-cjs-'));
  t.after(() => rmSync(out, { recursive: true, force: true }));
  const tsc = join(root, 'node_modules/typescript-7/bin/tsc');
  spawnSync(process.execPath, [tsc, '-p', 'tsconfig.cjs.json', '--outDir', out, '--declaration', 'false', '--sourceMap', 'false'], { cwd: root, stdio: 'ignore' });
  assert.ok(existsSync(join(out, 'index.js')), 'tsc -p tsconfig.cjs.json emitted index.js');
  assert.ok(!existsSync(join(out, 'internal.js')), 'the internal entry is not part of the package');
  writeFileSync(join(out, 'package.json'), JSON.stringify({ type: 'commonjs' }));
  const cjs = createRequire(join(out, 'index.js'))(join(out, 'index.js')) as Record<string, unknown>;
  assert.deepEqual(sorted(Object.keys(cjs)), sorted(publicValues), 'dist/cjs');
});
