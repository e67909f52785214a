// The instanced-transforms comparison scene (issue 25): fixtures/instanced-transforms/scene.glb,
// shared meshes placed by reused nodes and EXT_mesh_gpu_instancing with rotations, non-uniform
// and mirroring scales, loaded through the public glTF loader and rendered to per-block
// statistics; Mitsuba 3 renders the same scene flattened by the generator
// (scripts/reference/instanced-transforms-scene.ts writes both, with scene.json). Used by
// instanced-transforms-reference.test.ts, and by anyone measuring it at more samples or through
// another acceleration path (`rendererOptions`).
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { loadGltfScene } from '../../src/io/index.ts';
import type { WavefrontPathTracingOptions } from '../../src/pathtracer/types.ts';
import { renderBlockStats, type BlockGrid, type BlockStats, type Vec3 } from '../helpers/block-reference.ts';

export interface InstancedTransformsSpec extends BlockGrid {
  maxDepth: number;
  /** Uniform environment radiance. */
  environment: Vec3;
}

const fixtures = new URL('./fixtures/instanced-transforms/', import.meta.url);

export function readInstancedFixture<T>(name: string): T {
  return JSON.parse(readFileSync(new URL(name, fixtures), 'utf8')) as T;
}

export const instancedTransformsSpec = readInstancedFixture<InstancedTransformsSpec>('scene.json');

/**
 * Loads scene.glb (its camera, meshes, instances, materials and emissive light), adds the
 * constant environment of scene.json, renders `spp` samples at the spec's depth and returns the
 * block statistics. `rendererOptions` go into the renderer options last (e.g. another
 * acceleration structure for the same scene).
 */
export async function renderInstancedTransforms(device: GPUDevice, spp: number, seed: number, rendererOptions: Partial<WavefrontPathTracingOptions> = {}): Promise<BlockStats & { invalidSamples: number }> {
  const spec = instancedTransformsSpec;
  const scene = await loadGltfScene(fileURLToPath(new URL('scene.glb', fixtures)));
  return renderBlockStats(spec, {
    ...scene, device, maxDepth: spec.maxDepth, samplesPerPixel: spp, seed,
    environment: { color: spec.environment },
    ...rendererOptions,
  });
}
