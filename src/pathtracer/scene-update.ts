/**
 * `updateScene`'s CPU half: validate new meshes, instances and lights against the renderer's
 * materials, pack the geometry (and, in 'cpu-upload' mode, build the BVH) and the light tables
 * again, and check that the result fits the device and the compiled kernels, all before the
 * renderer changes anything.
 */
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { fail } from '../errors/validate.ts';
import { buildGpuLighting, type GpuLighting } from '../lighting/gpu-lighting.ts';
import { validateLightingOptions, type LightingConfig, type WavefrontLightingOptions } from '../lighting/lighting-options.ts';
import { normalizeSceneUpdate, type NormalizedScene } from '../scene/normalize-scene.ts';
import type { ShaderFeatures } from '../shaders/features.ts';
import { checkBufferLimits, planBuffers, type PlannedBuffer, type PlannedBufferName } from './buffer-plan.ts';
import { normalizeWavefrontCamera, type WavefrontCamera } from './camera.ts';
import type { WavefrontPathTracingComputeConfig } from './config.ts';
import { planInput, sceneFeatures } from './scene-plan.ts';
import { prepareGeometry, type PreparedMaterials, type PreparedScene } from './scene/prepare-scene.ts';
import type { WavefrontPathTracingOptions, WavefrontSceneUpdate } from './types.ts';

/** The lighting options a renderer keeps to validate new lights against (the environment stays). */
export type LightingSources = WavefrontLightingOptions & { lights?: unknown };

/** What a renderer keeps to rebuild its geometry (besides its current normalized scene). */
export interface SceneSources {
  materials: PreparedMaterials;
  /** The shader features the kernels were compiled with. */
  features: ShaderFeatures;
  lightingOptions: LightingSources;
}

const lightingKeys = ['environmentMap', 'environmentLighting', 'environmentPortals', 'environmentPortalMode', 'lightSampler', 'environmentSampling', 'lights'] as const;

export function lightingOptionsOf(options: WavefrontPathTracingOptions): LightingSources {
  const out: Record<string, unknown> = {};
  for (const key of lightingKeys) if (options[key] !== undefined) out[key] = options[key];
  return out as LightingSources;
}

export interface PreparedSceneUpdate {
  scene: NormalizedScene;
  prepared: PreparedScene;
  /** The buffer sizes of the new scene. */
  plan: Record<PlannedBufferName, PlannedBuffer>;
  lighting: GpuLighting;
  lightingConfig: LightingConfig;
  lightingOptions: LightingSources;
  camera: WavefrontCamera | undefined;
}

const updateKeys: ReadonlySet<string> = new Set<keyof WavefrontSceneUpdate>(['meshes', 'instances', 'lights', 'camera']);

/** The update field a newly needed shader feature comes from, for the error. */
function featureField(feature: string, update: WavefrontSceneUpdate): string {
  const lightFeature = /PUNCTUAL|AREA|LIGHT_TREE/.test(feature);
  if (lightFeature && update.lights !== undefined) return 'lights';
  return update.meshes !== undefined ? 'meshes' : update.instances !== undefined ? 'instances' : 'lights';
}

export async function prepareSceneUpdate(
  base: NormalizedScene,
  sources: SceneSources,
  config: WavefrontPathTracingComputeConfig,
  update: WavefrontSceneUpdate,
  limits: GPUSupportedLimits,
): Promise<PreparedSceneUpdate> {
  if (typeof update !== 'object' || update === null) fail('INVALID_OPTION', 'update', 'expected { meshes?, instances?, lights?, camera? }');
  for (const key of Object.keys(update)) {
    if (!updateKeys.has(key)) fail('INVALID_OPTION', key, `updateScene does not change ${key} (it replaces meshes, instances, lights and the camera)`);
  }
  const camera = update.camera === undefined ? undefined : normalizeWavefrontCamera(update.camera);
  const scene = normalizeSceneUpdate(base, update);
  const lightingOptions = update.lights === undefined ? sources.lightingOptions : { ...sources.lightingOptions, lights: update.lights };
  const lightingConfig = update.lights === undefined ? config.lighting : validateLightingOptions(lightingOptions, config.environment);
  const next = { ...config, lighting: lightingConfig };
  const estimate = planInput(next, scene);
  checkBufferLimits(limits, planBuffers(estimate));
  const prepared = await prepareGeometry(scene, sources.materials, { accelerationBuildMode: config.accelerationBuildMode, instancing: config.instancing });
  const lighting = buildGpuLighting({ config: lightingConfig, triangles: { records: prepared.lights, count: prepared.lightCount }, sceneCenter: prepared.sceneCenter, sceneRadius: prepared.sceneRadius });
  const plan = planBuffers({ ...estimate, lightCount: prepared.lightCount, lightHeapCells: lighting.heap.byteLength / 16 });
  checkBufferLimits(limits, plan);
  // The device's choice stays what the kernels were built with.
  const features = sceneFeatures(prepared, lighting, next, { softwareAdapter: !sources.features.FEATURE_WORKGROUP_TALLIES });
  const missing = (Object.keys(features) as (keyof ShaderFeatures)[]).filter((k) => features[k] && !sources.features[k]);
  if (missing.length > 0) {
    throw new GpuRendererError(
      'INVALID_STATE',
      `the updated scene needs shader features the kernels were specialised without (${missing.join(', ')}); create a new renderer, or one with shaderSpecialization: 'off'`,
      { field: featureField(missing[0]!, update) },
    );
  }
  return { scene, prepared, plan, lighting, lightingConfig, lightingOptions, camera };
}
