/**
 * One path tracer for a whole sequence: the first frame creates it; a later frame of the same
 * topology (the same meshes with the same triangles, materials and attributes, the same instances
 * of them, the same lights: an animation's next pose) moves it with `updateGeometry` (new vertices
 * and transforms, the BVH refitted on the GPU); any other frame (a variant's materials, meshes that
 * appear, moved punctual lights) replaces its geometry with `updateScene` (the BVH built anew).
 * Materials, textures, the environment and the compiled kernels stay throughout. A frame whose
 * materials, textures or images are other arrays (another asset), or that needs a shader feature
 * the kernels were specialised without (a variant's first alpha-tested material), gets a new
 * renderer.
 */
import { isGpuRendererError } from '../errors/gpu-renderer-error.ts';
import { createWavefrontPathTracingComputeRenderer } from '../pathtracer/renderer.ts';
import type { BvhUpdateMode, WavefrontPathTracingOptions, WavefrontPathTracingRenderer } from '../pathtracer/types.ts';
import type { WavefrontMeshInput, WavefrontSceneDescription } from '../scene/types.ts';

/** Renderer options without the scene (each frame brings its own). */
export type SequenceRendererOptions = Omit<WavefrontPathTracingOptions, 'meshes' | 'instances' | 'materials' | 'textures' | 'images' | 'lights' | 'camera'>;

export interface SequenceRendererSettings {
  /** How `updateGeometry` brings the BVH along between frames of one topology: 'refit' (default) or 'rebuild'. */
  bvh?: BvhUpdateMode;
}

export interface SequenceRenderer {
  /** The renderer showing `scene`, accumulation restarted: updated in place when it can be, else new. */
  show(scene: WavefrontSceneDescription): Promise<WavefrontPathTracingRenderer>;
  /** The current renderer, if any. */
  readonly renderer: WavefrontPathTracingRenderer | null;
  /** How many renderers were created (1 for a sequence updated in place throughout). */
  readonly created: number;
  /** How frames were shown: created, moved (`updateGeometry`) or replaced (`updateScene`). */
  readonly counts: { readonly created: number; readonly moved: number; readonly replaced: number };
  destroy(): void;
}

function sameArray(a: ArrayLike<number> | undefined, b: ArrayLike<number> | undefined): boolean {
  if (a === b) return true;
  if (a === undefined || b === undefined || a.length !== b.length) return false;
  for (let i = 0; i < a.length; i++) if (a[i] !== b[i]) return false;
  return true;
}

const IDENTITY = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];

/**
 * Whether `next` is known to hold what `previous` held: a different array with the same values
 * (what a new pose gives an unmoved mesh). The same array object is not known to be unchanged:
 * it may have been written in place since.
 */
function knownUnchanged(previous: ArrayLike<number> | undefined, next: ArrayLike<number> | undefined): boolean {
  if (previous === undefined || next === undefined) return previous === next;
  return previous !== next && sameArray(previous, next);
}

/** The same vertex data (what updateGeometry moves). */
function sameVertices(a: WavefrontMeshInput, b: WavefrontMeshInput): boolean {
  return knownUnchanged(a.positions, b.positions) && knownUnchanged(a.normals, b.normals) && knownUnchanged(a.tangents, b.tangents);
}

/** The same mesh but for its vertex positions, normals and tangents (what updateGeometry moves). */
function sameMeshTopology(a: WavefrontMeshInput, b: WavefrontMeshInput): boolean {
  return (
    a.positions.length === b.positions.length &&
    a.material === b.material &&
    (a.normals === undefined) === (b.normals === undefined) &&
    (a.tangents === undefined) === (b.tangents === undefined) &&
    sameArray(a.indices, b.indices) &&
    sameArray(a.uvs, b.uvs) &&
    sameArray(a.uvs1, b.uvs1) &&
    sameArray(a.colors, b.colors)
  );
}

/** Whether `next` is `previous` with moved vertices and instance transforms only. */
export function sameTopology(previous: WavefrontSceneDescription, next: WavefrontSceneDescription): boolean {
  const pm = previous.meshes ?? [];
  const nm = next.meshes ?? [];
  const pi = previous.instances;
  const ni = next.instances;
  if (pm.length !== nm.length || (pi === undefined) !== (ni === undefined) || (pi?.length ?? 0) !== (ni?.length ?? 0)) return false;
  if (!pm.every((mesh, i) => sameMeshTopology(mesh, nm[i]!))) return false;
  if (pi !== undefined && !pi.every((inst, i) => inst.mesh === ni![i]!.mesh && inst.material === ni![i]!.material)) return false;
  return JSON.stringify(previous.lights ?? []) === JSON.stringify(next.lights ?? []);
}

export function createSequenceRenderer(options: SequenceRendererOptions, settings: SequenceRendererSettings = {}): SequenceRenderer {
  let renderer: WavefrontPathTracingRenderer | null = null;
  let shown: WavefrontSceneDescription | null = null;
  const counts = { created: 0, moved: 0, replaced: 0 };
  const create = async (scene: WavefrontSceneDescription): Promise<WavefrontPathTracingRenderer> => {
    renderer?.destroy();
    renderer = null;
    renderer = await createWavefrontPathTracingComputeRenderer({ ...options, ...scene } as WavefrontPathTracingOptions);
    counts.created += 1;
    return renderer;
  };
  const update = async (current: WavefrontPathTracingRenderer, previous: WavefrontSceneDescription, scene: WavefrontSceneDescription): Promise<void> => {
    if (sameTopology(previous, scene)) {
      // Only what changed: a rigid animation moves instances alone, which patches their top-level
      // records (top-level-patch.ts) instead of refitting every shared mesh's bottom level.
      const before = previous.meshes ?? [];
      const previousInstances = previous.instances ?? [];
      await current.updateGeometry({
        meshes: (scene.meshes ?? []).map((m, i) => (sameVertices(before[i]!, m) ? null : { positions: m.positions, ...(m.normals ? { normals: m.normals } : {}), ...(m.tangents ? { tangents: m.tangents } : {}) })),
        ...(scene.instances ? { instances: scene.instances.map((inst, i) => ((inst.transform === undefined ? previousInstances[i]?.transform === undefined : knownUnchanged(previousInstances[i]?.transform ?? IDENTITY, inst.transform)) ? null : { transform: inst.transform ?? IDENTITY })) } : {}),
        bvh: settings.bvh ?? 'refit',
      });
      if (scene.camera) current.updateCamera(scene.camera);
      counts.moved += 1;
      return;
    }
    await current.updateScene({ meshes: scene.meshes ?? [], instances: scene.instances ?? [], lights: scene.lights ?? [], ...(scene.camera ? { camera: scene.camera } : {}) });
    counts.replaced += 1;
  };
  return {
    async show(scene) {
      const sameMaterials = shown !== null && shown.materials === scene.materials && shown.textures === scene.textures && shown.images === scene.images && shown.sceneObjects === scene.sceneObjects;
      const current = renderer;
      if (current === null || shown === null || !sameMaterials) {
        const created = await create(scene);
        shown = scene;
        return created;
      }
      try {
        await update(current, shown, scene);
      } catch (error) {
        // Kernels specialised without a feature this frame needs (or light tables that outgrew
        // their buffer): compile a renderer for it.
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
      return counts.created;
    },
    get counts() {
      return { ...counts };
    },
    destroy() {
      renderer?.destroy();
      renderer = null;
      shown = null;
    },
  };
}
