/**
 * What a scene asks of the path tracer before anything is allocated: the buffer sizes it implies
 * (checked against the device's limits) and the shader features it needs (the rest are compiled out).
 */
import type { GpuLighting } from '../lighting/gpu-lighting.ts';
import type { NormalizedScene } from '../scene/normalize-scene.ts';
import type { ShaderFeatures } from '../shaders/features.ts';
import type { BufferPlanInput } from './buffer-plan.ts';
import type { WavefrontPathTracingComputeConfig } from './config.ts';
import { materialFeatures } from './scene/material-features.ts';
import { materialHeapCells } from './scene/pack-materials.ts';
import { vertexStreamBytes } from './scene/pack-vertices.ts';
import { denoiserFilmReads } from '../film/denoise/registry.ts';
import type { PreparedScene } from './scene/prepare-scene.ts';
import { bvhNodeCapacity, planInstancing, primitiveRecordCount, type InstancingPlan } from './scene/instancing.ts';

/**
 * Sizes known from the validated scene, before the BVH is built: what the first limit check uses.
 * The wave buffers are sized for waves of `wavePaths` paths (the renderer's bound; a scene update,
 * which leaves them alone, checks the scene's buffers with the default).
 */
export function planInput(config: WavefrontPathTracingComputeConfig, scene: NormalizedScene, wavePaths = 1): BufferPlanInput {
  let lights = 0;
  for (const inst of scene.instances) {
    const material = scene.materials[inst.material ?? scene.meshMaterials[inst.mesh]!]!;
    if (material.emission.some((c) => c > 0)) lights += scene.meshes[inst.mesh]!.triangleCount;
  }
  const instancing = planInstancing(scene, config.instancing);
  return {
    width: config.width,
    height: config.height,
    wavePaths,
    maxDepth: config.maxDepth,
    aovs: outputFeatures(config).aovs,
    output: { moments: outputFeatures(config).moments, adaptive: config.output.adaptive !== null, denoise: config.output.denoise !== null, atrous: config.output.denoise?.denoiser === 'atrous' },
    wavesPerSubmission: config.output.maxFramePassesPerSubmission,
    framesInFlight: config.framesInFlight,
    ...vertexStreamBytes(scene.meshes),
    primitiveCount: primitiveRecordCount(instancing),
    bvhNodeCount: bvhNodeCapacity(instancing),
    geometry: geometryDescription(instancing, scene),
    alphaPrimitiveCount: instancing.alphaTriangles,
    instanceCount: scene.instances.length + scene.sceneObjects.length,
    lightCount: lights,
    // Cores, extension blocks and texture bindings (the exact heap, tables included, is checked after packing).
    materialCells: materialHeapCells([...scene.materials, ...scene.sceneObjects.map((o) => o.material)]),
  };
}

/** What the primitive records hold, for SCENE_TOO_LARGE errors. */
function geometryDescription(plan: InstancingPlan, scene: NormalizedScene): string {
  const shared = plan.bottomLevels.length > 0 ? `, ${plan.placements} placements of ${plan.bottomLevels.length} shared meshes (${plan.bottomLevelTriangles} triangles stored once)` : '';
  return `${plan.flattenedTriangles} flattened triangles${shared}, ${scene.sceneObjects.length} analytic shapes`;
}

/**
 * Output accumulation the options need: the AOVs and moments for readAov, the moments for adaptive
 * sampling, and what the denoiser reads.
 */
export function outputFeatures(config: WavefrontPathTracingComputeConfig): { aovs: boolean; moments: boolean } {
  const denoiser = config.output.denoise ? denoiserFilmReads(config.output.denoise.denoiser) : { aovs: false, moments: false };
  return { aovs: config.aovs || denoiser.aovs, moments: config.aovs || denoiser.moments || config.output.adaptive !== null };
}

/**
 * The shader features a scene needs on a device; everything else is compiled out. The device
 * only chooses how statistics are reduced (a CPU adapter adds them per invocation).
 */
export function sceneFeatures(prepared: PreparedScene, lighting: GpuLighting, config: WavefrontPathTracingComputeConfig, device: { softwareAdapter: boolean }): ShaderFeatures {
  return {
    FEATURE_ANALYTIC_SHAPES: prepared.uses.analyticShapes,
    FEATURE_INSTANCING: prepared.uses.instancing,
    FEATURE_ALPHA_TEST: prepared.uses.alphaTest,
    FEATURE_TEXTURES: prepared.uses.textures,
    FEATURE_EMISSIVE_LIGHTS: prepared.uses.emissiveLights,
    FEATURE_ENVIRONMENT: lighting.uses.environment,
    FEATURE_ENVIRONMENT_MAP: lighting.uses.environmentMap,
    FEATURE_SUN: lighting.uses.sun,
    FEATURE_PORTALS: lighting.uses.portals,
    FEATURE_PUNCTUAL_LIGHTS: lighting.uses.punctualLights,
    FEATURE_AREA_LIGHTS: lighting.uses.areaLights,
    FEATURE_LIGHT_TREE: lighting.uses.lightTree,
    FEATURE_AOVS: outputFeatures(config).aovs,
    FEATURE_FILM_MOMENTS: outputFeatures(config).moments,
    FEATURE_ADAPTIVE_SAMPLING: config.output.adaptive !== null,
    ...materialFeatures(prepared.uses.materials),
    FEATURE_WORKGROUP_TALLIES: !device.softwareAdapter,
  };
}

