// Creates the path tracer for a scene, leaving out what this version of the renderer refuses
// instead of failing the whole asset: a glTF file's punctual lights, or a KHR material extension
// the BSDF does not implement yet. The renderer names the refused field in a typed error; the demo
// drops that key everywhere, notes it, and tries again. As the renderer gains a feature, the error
// stops and nothing is dropped: this file needs no change.
import {
  GpuRendererError,
  createWavefrontPathTracingComputeRenderer,
  type WavefrontMaterialInput,
  type WavefrontPathTracingOptions,
  type WavefrontPathTracingRenderer,
} from '@plasius/gpu-renderer';

/**
 * The glTF core material keys; every other material key belongs to a KHR extension (the renderer
 * accepts or refuses each one by name), which the demo may leave out.
 */
const coreMaterialKeys = new Set([
  'name', 'baseColorFactor', 'baseColorTexture', 'metallicFactor', 'roughnessFactor', 'metallicRoughnessTexture', 'normalTexture',
  'occlusionTexture', 'emissiveFactor', 'emissiveTexture', 'emissiveStrength', 'ior', 'doubleSided', 'alphaMode', 'alphaCutoff',
]);

export interface RenderableScene {
  renderer: WavefrontPathTracingRenderer;
  /** What was left out, one line each. */
  omitted: string[];
}

export async function createRendererLeavingOutUnsupported(options: WavefrontPathTracingOptions): Promise<RenderableScene> {
  const omitted: string[] = [];
  let current = options;
  for (let attempt = 0; attempt < 64; attempt++) {
    try {
      return { renderer: await createWavefrontPathTracingComputeRenderer(current), omitted };
    } catch (error) {
      const next = error instanceof GpuRendererError ? withoutRefused(current, error, omitted) : undefined;
      if (!next) throw error;
      current = next;
    }
  }
  throw new Error('too many unsupported features');
}

function withoutRefused(options: WavefrontPathTracingOptions, error: GpuRendererError, omitted: string[]): WavefrontPathTracingOptions | undefined {
  const field = error.field ?? '';
  if (error.code === 'INVALID_OPTION' && field === 'lights' && options.lights?.length) {
    omitted.push(`${options.lights.length} punctual light(s): not rendered by this version (emissive surfaces and the environment light the scene)`);
    return { ...options, lights: [] };
  }
  // The refused key, without a component index (sheenColorFactor[2]).
  const key = (field.split('.').pop() ?? '').replace(/\[\d+\]$/, '');
  if (error.code === 'INVALID_MATERIAL' && field.includes('.') && !coreMaterialKeys.has(key)) {
    omitted.push(`material ${key}: not rendered by this version (${error.message})`);
    const strip = (m: WavefrontMaterialInput): WavefrontMaterialInput => {
      if (!(key in m)) return m;
      const copy = { ...m } as Record<string, unknown>;
      delete copy[key];
      return copy as WavefrontMaterialInput;
    };
    return {
      ...options,
      ...(options.materials ? { materials: options.materials.map(strip) } : {}),
      ...(options.meshes ? { meshes: options.meshes.map((mesh) => (typeof mesh.material === 'object' ? { ...mesh, material: strip(mesh.material) } : mesh)) } : {}),
    };
  }
  return undefined;
}
