/**
 * One path tracer for a whole sequence: the first frame creates it, every later frame updates its
 * geometry, lights and camera in place (`updateScene`: the BVH and geometry buffers are rebuilt,
 * materials, textures, the environment and the compiled kernels stay). A frame whose materials,
 * textures or images are other arrays (another asset), or that needs a shader feature the kernels
 * were specialised without (a variant's first alpha-tested material), gets a new renderer.
 */
import { isGpuRendererError } from '../errors/gpu-renderer-error.ts';
import { createWavefrontPathTracingComputeRenderer } from '../pathtracer/renderer.ts';
import type { WavefrontPathTracingOptions, WavefrontPathTracingRenderer } from '../pathtracer/types.ts';
import type { WavefrontSceneDescription } from '../scene/types.ts';

/** Renderer options without the scene (each frame brings its own). */
export type SequenceRendererOptions = Omit<WavefrontPathTracingOptions, 'meshes' | 'instances' | 'materials' | 'textures' | 'images' | 'lights' | 'camera'>;

export interface SequenceRenderer {
  /** The renderer showing `scene`, accumulation restarted: updated in place when it can be, else new. */
  show(scene: WavefrontSceneDescription): Promise<WavefrontPathTracingRenderer>;
  /** The current renderer, if any. */
  readonly renderer: WavefrontPathTracingRenderer | null;
  /** How many renderers were created (1 for a sequence updated in place throughout). */
  readonly created: number;
  destroy(): void;
}

export function createSequenceRenderer(options: SequenceRendererOptions): SequenceRenderer {
  let renderer: WavefrontPathTracingRenderer | null = null;
  let shown: WavefrontSceneDescription | null = null;
  let created = 0;
  const create = async (scene: WavefrontSceneDescription): Promise<WavefrontPathTracingRenderer> => {
    renderer?.destroy();
    renderer = null;
    renderer = await createWavefrontPathTracingComputeRenderer({ ...options, ...scene } as WavefrontPathTracingOptions);
    created += 1;
    return renderer;
  };
  return {
    async show(scene) {
      const sameMaterials = shown !== null && shown.materials === scene.materials && shown.textures === scene.textures && shown.images === scene.images && shown.sceneObjects === scene.sceneObjects;
      const current = renderer;
      if (current === null || !sameMaterials) {
        const created = await create(scene);
        shown = scene;
        return created;
      }
      try {
        await current.updateScene({ meshes: scene.meshes ?? [], instances: scene.instances ?? [], lights: scene.lights ?? [], ...(scene.camera ? { camera: scene.camera } : {}) });
      } catch (error) {
        // Kernels specialised without a feature this frame needs: compile a renderer for it.
        if (!isGpuRendererError(error) || error.code !== 'INVALID_STATE') throw error;
        await create(scene);
      }
      shown = scene;
      return renderer!;
    },
    get renderer() {
      return renderer;
    },
    get created() {
      return created;
    },
    destroy() {
      renderer?.destroy();
      renderer = null;
      shown = null;
    },
  };
}
