import { normalizeWavefrontScene } from '../../scene/normalize-scene.ts';
import type { WavefrontMeshInput, WavefrontSceneDescription, WavefrontSceneObjectInput } from '../../scene/types.ts';
import { flattenPrimitives } from './flatten-primitives.ts';
import { planInstancing } from './instancing.ts';
import { packPrimitives } from '../../accel/triangle-packing.ts';
import { packVertexStreams, type PackedVertexStreams } from './pack-vertices.ts';
import { prepareScene, type PreparedScene } from './prepare-scene.ts';

/** What the path tracer uploads for a scene: primitives in BVH order, nodes, streams, materials, lights. */
export type WavefrontMeshAcceleration = PreparedScene;

const noTextures = (): number => {
  throw new Error('unreachable: a scene without textures has no texture infos');
};

/**
 * Builds everything the path tracer uploads for meshes (or a whole scene): validated streams, the
 * binned-SAH BVH over all primitives, the material heap and the light table. Device limits default
 * to WebGPU's guaranteed minimums for the texture atlas.
 */
export async function createWavefrontMeshAcceleration(
  scene: readonly WavefrontMeshInput[] | WavefrontSceneDescription,
  limits: { maxTextureDimension2D: number; maxTextureArrayLayers: number } = { maxTextureDimension2D: 8192, maxTextureArrayLayers: 256 },
): Promise<WavefrontMeshAcceleration> {
  const description = Array.isArray(scene) ? { meshes: [...scene] } : (scene as WavefrontSceneDescription);
  return prepareScene(normalizeWavefrontScene(description), limits);
}

/** The meshes' indexed vertex streams as the GPU reads them (Vertex records and one index buffer). */
export function createWavefrontGpuMeshSource(meshes: readonly WavefrontMeshInput[]): PackedVertexStreams {
  return packVertexStreams(normalizeWavefrontScene({ meshes: [...meshes] }).meshes);
}

/** Analytic scene objects as the Primitive records the traversal intersects (sphere or box shapes). */
export function packWavefrontSceneObjects(sceneObjects: readonly WavefrontSceneObjectInput[]): ArrayBuffer {
  const scene = normalizeWavefrontScene({ sceneObjects: [...sceneObjects] });
  const flat = flattenPrimitives(scene, noTextures, planInstancing(scene, 'off'));
  return packPrimitives(flat, Uint32Array.from({ length: flat.count }, (_, i) => i));
}
