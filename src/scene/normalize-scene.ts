import { describe, fail } from '../errors/validate.ts';
import { normalizeWavefrontInstance, identityTransform, affineFromColumnMajor, type NormalizedInstance } from './instance.ts';
import { normalizeMaterial, type NormalizedMaterial } from './material.ts';
import { normalizeWavefrontMesh, type NormalizedMesh } from './mesh.ts';
import { normalizeWavefrontSceneObject, type NormalizedSceneObject } from './scene-object.ts';
import type { WavefrontImageInput, WavefrontSceneDescription, WavefrontTextureInput } from './types.ts';

/**
 * A validated scene in the renderer-agnostic representation the path tracer and the raster renderer
 * share: meshes (object-space vertex streams), one material list, explicit instances, textures.
 */
export interface NormalizedScene {
  meshes: NormalizedMesh[];
  /** Scene materials first, then one per inline mesh material. */
  materials: NormalizedMaterial[];
  /** Where each material came from, for error messages (`materials[2]`, `meshes[5].material`). */
  materialFields: string[];
  /** Material index of each mesh. */
  meshMaterials: number[];
  /** How many of `materials` are the scene's own (the rest are inline mesh materials). */
  sceneMaterialCount: number;
  /** The placements drawn: the scene's `instances`, or one identity placement per mesh. */
  instances: NormalizedInstance[];
  sceneObjects: NormalizedSceneObject[];
  textures: readonly WavefrontTextureInput[];
  images: readonly WavefrontImageInput[];
  /** Triangles over all instances. */
  triangleCount: number;
}

function arrayOf(value: unknown, field: string, code: 'INVALID_MESH' | 'INVALID_MATERIAL' | 'INVALID_INSTANCE' | 'INVALID_SCENE_OBJECT' | 'INVALID_TEXTURE'): unknown[] {
  if (value === undefined) return [];
  if (!Array.isArray(value)) fail(code, field, `expected an array, got ${describe(value)}`);
  return value;
}

/** Validates every part of a scene at the public boundary: typed errors naming the field. */
export function normalizeWavefrontScene(scene: Pick<WavefrontSceneDescription, 'meshes' | 'instances' | 'materials' | 'textures' | 'images' | 'sceneObjects'>): NormalizedScene {
  const textures = arrayOf(scene.textures, 'textures', 'INVALID_TEXTURE') as WavefrontTextureInput[];
  const images = arrayOf(scene.images, 'images', 'INVALID_TEXTURE') as WavefrontImageInput[];
  const materials = (arrayOf(scene.materials, 'materials', 'INVALID_MATERIAL') as (WavefrontSceneDescription['materials'] & object)).map((m, i) =>
    normalizeMaterial(m, `materials[${i}]`, { textureCount: textures.length }),
  );
  const sceneMaterialCount = materials.length;
  const materialFields = materials.map((_, i) => `materials[${i}]`);
  const meshes = (arrayOf(scene.meshes, 'meshes', 'INVALID_MESH') as (WavefrontSceneDescription['meshes'] & object)).map((m, i) =>
    normalizeWavefrontMesh(m, i, `meshes[${i}]`, { materialCount: sceneMaterialCount, textureCount: textures.length }),
  );
  const meshMaterials = meshes.map((mesh, i) => {
    if (typeof mesh.material === 'number') return mesh.material;
    materials.push(mesh.material);
    materialFields.push(`meshes[${i}].material`);
    return materials.length - 1;
  });
  const instances = normalizeInstances(scene.instances, meshes, sceneMaterialCount);
  const sceneObjects = (arrayOf(scene.sceneObjects, 'sceneObjects', 'INVALID_SCENE_OBJECT') as (WavefrontSceneDescription['sceneObjects'] & object)).map((o, i) =>
    normalizeWavefrontSceneObject(o, i),
  );
  const triangleCount = instances.reduce((n, inst) => n + meshes[inst.mesh]!.triangleCount, 0);
  return { meshes, materials, materialFields, meshMaterials, sceneMaterialCount, instances, sceneObjects, textures, images, triangleCount };
}

function normalizeInstances(instances: unknown, meshes: readonly NormalizedMesh[], materialCount: number): NormalizedInstance[] {
  if (instances === undefined) {
    const identity = affineFromColumnMajor(identityTransform, 'instances');
    return meshes.map((mesh, i) => ({ id: mesh.id, mesh: i, material: null, ...identity }));
  }
  return arrayOf(instances, 'instances', 'INVALID_INSTANCE').map((inst, i) => normalizeWavefrontInstance(inst as never, i, { meshes: meshes.length, materials: materialCount }));
}

/**
 * A scene with new meshes and/or instances over the materials, textures and analytic objects of
 * `base` (validated as `normalizeWavefrontScene` does); without new instances the current ones
 * place the new meshes. Meshes refer to the scene's materials by
 * index: an inline mesh material would change the material heap, which an update keeps, and is an
 * INVALID_MESH error naming it.
 */
export function normalizeSceneUpdate(base: NormalizedScene, update: Pick<WavefrontSceneDescription, 'meshes' | 'instances'>): NormalizedScene {
  const textureCount = base.textures.length;
  let meshes = base.meshes;
  let meshMaterials = base.meshMaterials;
  if (update.meshes !== undefined) {
    meshes = (arrayOf(update.meshes, 'meshes', 'INVALID_MESH') as (WavefrontSceneDescription['meshes'] & object)).map((m, i) =>
      normalizeWavefrontMesh(m, i, `meshes[${i}]`, { materialCount: base.sceneMaterialCount, textureCount }),
    );
    meshMaterials = meshes.map((mesh, i) => {
      if (typeof mesh.material !== 'number') fail('INVALID_MESH', `meshes[${i}].material`, 'a scene update keeps the material heap: refer to a scene material by index');
      return mesh.material;
    });
  }
  let instances = base.instances;
  if (update.instances !== undefined) {
    instances = normalizeInstances(update.instances, meshes, base.sceneMaterialCount);
  } else {
    instances.forEach((inst, i) => {
      if (inst.mesh >= meshes.length) fail('INVALID_INSTANCE', `instances[${i}].mesh`, `mesh ${inst.mesh} is out of range: the update has ${meshes.length} meshes`);
    });
  }
  const triangleCount = instances.reduce((n, inst) => n + meshes[inst.mesh]!.triangleCount, 0);
  return { ...base, meshes, meshMaterials, instances, triangleCount };
}
