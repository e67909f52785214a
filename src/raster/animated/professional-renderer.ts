/**
 * createProfessionalAnimatedSceneRenderer: the fail-closed entry point. Before any GPU work it
 * requires a skinned model whose skinned primitives have normals, TEXCOORD_0 and materials with base
 * colour and normal textures, and authored-root-motion movement profiles for every clip a travel or
 * jump beat plays (src/animation/character-requirements.ts); WebGPU itself must be available
 * (WEBGPU_UNAVAILABLE otherwise). Anything missing is a typed error naming it; there is no fallback.
 */
import { GpuRendererError } from '../../errors/gpu-renderer-error.ts';
import { getGpu } from '../../gpu/acquire-device.ts';
import { createAnimatedRenderer } from './animated-scene-renderer.ts';
import type { AnimatedSceneRenderer, AnimatedSceneRendererOptions } from './animated-types.ts';

export async function createProfessionalAnimatedSceneRenderer(options: AnimatedSceneRendererOptions): Promise<AnimatedSceneRenderer> {
  if (options?.device === undefined && (await getGpu()) === undefined) {
    throw new GpuRendererError('WEBGPU_UNAVAILABLE', 'the professional animated scene renderer needs WebGPU (no navigator.gpu and no Dawn); it has no 2D fallback', { field: 'canvas' });
  }
  return createAnimatedRenderer(options, { professional: true });
}
