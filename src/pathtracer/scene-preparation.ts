import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { fail } from '../errors/validate.ts';
import {
  bvhNodeLayout,
  dynamicUniformStride,
  pathStateLayout,
  rendererWavefrontAccumulationTexelBytes,
  shadowRayLayout,
  triangleAttributesLayout,
  triangleLayout,
} from '../gpu-layout/records.ts';
import { luminance } from '../lighting/emissive-lights.ts';
import { normalizeWavefrontMesh, type NormalizedMesh } from '../scene/mesh.ts';
import { packWavefrontMaterials } from '../scene/material-packing.ts';
import { normalizeWavefrontSceneObject, packWavefrontSceneObjects, type NormalizedSceneObject } from '../scene/scene-object.ts';
import type { WavefrontMeshInput, WavefrontSceneObjectInput } from '../scene/types.ts';
import type { WavefrontPathTracingComputeConfig } from './config.ts';
import { createWavefrontMeshAccelerationAsync, type WavefrontMeshAcceleration } from './mesh-acceleration.ts';

/** Validated scene input, before any GPU work. */
export interface ValidatedWavefrontScene {
  meshes: NormalizedMesh[];
  sceneObjects: NormalizedSceneObject[];
  triangleCount: number;
}

/** Every mesh and scene object validated at the public boundary (typed errors naming the field). */
export function validateWavefrontScene(meshes: unknown, sceneObjects: unknown): ValidatedWavefrontScene {
  if (meshes !== undefined && !Array.isArray(meshes)) fail('INVALID_MESH', 'meshes', 'expected an array of meshes');
  if (sceneObjects !== undefined && !Array.isArray(sceneObjects)) fail('INVALID_SCENE_OBJECT', 'sceneObjects', 'expected an array of scene objects');
  const normalizedMeshes = ((meshes ?? []) as WavefrontMeshInput[]).map((m, i) => normalizeWavefrontMesh(m, i));
  const objects = ((sceneObjects ?? []) as WavefrontSceneObjectInput[]).map((o, i) => normalizeWavefrontSceneObject(o, i));
  return { meshes: normalizedMeshes, sceneObjects: objects, triangleCount: normalizedMeshes.reduce((n, m) => n + m.triangleCount, 0) };
}

/** Byte sizes of every buffer a render needs, computed before anything is allocated. */
export function wavefrontBufferPlan(triangleCount: number, sceneObjectCount: number, config: Pick<WavefrontPathTracingComputeConfig, 'width' | 'height' | 'tileSize' | 'maxDepth'>) {
  const capacity = Math.min(config.tileSize * config.tileSize, config.width * config.height);
  return {
    capacity,
    triangles: Math.max(1, triangleCount) * triangleLayout.size,
    triangleAttributes: Math.max(1, triangleCount) * triangleAttributesLayout.size,
    // A binary BVH over n triangles has at most 2n - 1 nodes.
    bvhNodes: Math.max(1, 2 * triangleCount - 1) * bvhNodeLayout.size,
    sceneObjects: Math.max(1, sceneObjectCount) * 32,
    paths: 2 * capacity * pathStateLayout.size,
    shadowRays: capacity * shadowRayLayout.size,
    tileRadiance: capacity * 16,
    accumulation: config.width * config.height * rendererWavefrontAccumulationTexelBytes,
    resolvedPixels: config.width * config.height * 4,
    bounceUniforms: (config.maxDepth + 1) * dynamicUniformStride,
  };
}

/**
 * Rejects, before any allocation, a scene or frame whose buffers exceed the device's limits,
 * naming the input responsible.
 */
export function checkWavefrontDeviceLimits(limits: GPUSupportedLimits, plan: ReturnType<typeof wavefrontBufferPlan>): void {
  const max = Math.min(limits.maxStorageBufferBindingSize, limits.maxBufferSize);
  const check = (bytes: number, field: string, what: string): void => {
    if (bytes > max) {
      throw new GpuRendererError('SCENE_TOO_LARGE', `${what} needs ${bytes} bytes but this device binds at most ${max} bytes per storage buffer`, { field });
    }
  };
  check(plan.triangles, 'meshes', 'the triangle buffer');
  check(plan.triangleAttributes, 'meshes', 'the triangle attribute buffer');
  check(plan.bvhNodes, 'meshes', 'the BVH node buffer');
  check(plan.sceneObjects, 'sceneObjects', 'the scene object buffer');
  check(plan.paths, 'tileSize', 'the path queues');
  check(plan.accumulation, 'width', 'the accumulation buffer (width x height)');
}

/** CPU-side scene data ready for upload. */
export interface PreparedWavefrontScene {
  mesh: WavefrontMeshAcceleration;
  materials: ArrayBuffer;
  sceneObjects: ArrayBuffer;
  sceneObjectCount: number;
  sceneCenter: [number, number, number];
  sceneRadius: number;
  /** Probability NEE picks the environment rather than an emissive triangle. */
  environmentSelectProbability: number;
}

export async function prepareWavefrontScene(scene: ValidatedWavefrontScene, environment: readonly number[]): Promise<PreparedWavefrontScene> {
  const mesh = await createWavefrontMeshAccelerationAsync(scene.meshes);
  const materials = [...mesh.source.materials, ...scene.sceneObjects.map((o) => o.material)];
  const objectMaterialIds = scene.sceneObjects.map((_, i) => mesh.source.materials.length + i);
  const min = [...mesh.bounds.min];
  const max = [...mesh.bounds.max];
  for (const o of scene.sceneObjects) {
    const lo = o.type === 'sphere' ? o.a.map((c) => c - o.b[0]) : o.a;
    const hi = o.type === 'sphere' ? o.a.map((c) => c + o.b[0]) : o.b;
    for (let c = 0; c < 3; c++) {
      min[c] = Math.min(min[c]!, lo[c]!);
      max[c] = Math.max(max[c]!, hi[c]!);
    }
  }
  const empty = !(min[0]! <= max[0]!);
  const sceneCenter: [number, number, number] = empty ? [0, 0, 0] : [0, 1, 2].map((c) => 0.5 * (min[c]! + max[c]!)) as [number, number, number];
  const sceneRadius = empty ? 1 : Math.max(1e-6, 0.5 * Math.hypot(max[0]! - min[0]!, max[1]! - min[1]!, max[2]! - min[2]!));
  // Selection in proportion to estimated power: the environment's flux through the scene's bounding
  // sphere (pi * 4 pi R^2 * L) against the emitters' flux. Any split in (0, 1) is unbiased; this
  // only steers variance, so it is bounded away from 0 and 1 to keep both strategies alive.
  const envLum = luminance(environment);
  let environmentSelectProbability = 0;
  if (envLum > 0) {
    if (mesh.lights.count === 0) environmentSelectProbability = 1;
    else {
      const envPower = envLum * 4 * Math.PI * Math.PI * sceneRadius * sceneRadius;
      environmentSelectProbability = Math.min(0.95, Math.max(0.05, envPower / (envPower + mesh.lights.totalPower)));
    }
  }
  return {
    mesh,
    materials: packWavefrontMaterials(materials),
    sceneObjects: packWavefrontSceneObjects(scene.sceneObjects, Math.max(1, scene.sceneObjects.length), objectMaterialIds),
    sceneObjectCount: scene.sceneObjects.length,
    sceneCenter,
    sceneRadius,
    environmentSelectProbability,
  };
}

