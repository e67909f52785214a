import { BufferUsage } from '../gpu/webgpu-constants.ts';
import type { GpuLighting } from '../lighting/gpu-lighting.ts';
import { uploadEnvironmentTexture } from '../lighting/upload-environment.ts';
import { uploadTextureAtlas } from '../materials/textures/upload-texture-atlas.ts';
import type { PathTracerResourceMap } from './bind-groups.ts';
import type { PlannedBuffer, PlannedBufferName } from './buffer-plan.ts';
import type { GpuBufferSet } from './gpu-buffers.ts';
import type { PreparedScene } from './scene/prepare-scene.ts';
import type { WavefrontMemoryStats } from './types.ts';

/** The renderer's GPU buffers (one per planned buffer) and textures, and the map the kernels bind. */
export interface RendererResources {
  resources: Record<PlannedBufferName, GPUBuffer>;
  resourceMap: PathTracerResourceMap;
  atlasTexture: GPUTexture;
  environmentTexture: GPUTexture;
  textureBytes: number;
}

/**
 * Creates every planned buffer (in `buffers`, which accounts their bytes), uploads the prepared
 * scene, the light tables and the textures once, and writes the lighting uniforms.
 */
export function uploadRendererResources(
  device: GPUDevice,
  buffers: GpuBufferSet,
  prepared: PreparedScene,
  lighting: GpuLighting,
  plan: Record<PlannedBufferName, PlannedBuffer>,
): RendererResources {
  const b = buffers;
  const S = BufferUsage.STORAGE;
  // The BVH buffers hold any tree of the scene (2n - 1 nodes), so a rebuild fits; in 'gpu' mode the
  // GPU build fills the top level (scene-acceleration.ts).
  const gpuBuild = prepared.acceleration.mode === 'gpu';
  const uploads: Partial<Record<PlannedBufferName, ArrayBuffer>> = {
    ...(gpuBuild ? {} : { primitives: prepared.primitives, bvhNodes: prepared.bvhNodes, bvhParents: prepared.bvhParents.buffer as ArrayBuffer }),
    alphaPrimitives: prepared.alphaPrimitives,
    instances: prepared.instances,
    indices: prepared.indices.buffer as ArrayBuffer,
    vertexStreams: prepared.vertexStreams.buffer as ArrayBuffer,
    materials: prepared.materials,
    lights: lighting.heap,
  };
  const usage: Partial<Record<PlannedBufferName, number>> = {
    frame: BufferUsage.UNIFORM | BufferUsage.COPY_DST,
    lighting: BufferUsage.UNIFORM | BufferUsage.COPY_DST,
    wave: BufferUsage.UNIFORM | BufferUsage.COPY_DST,
    bounce: BufferUsage.UNIFORM | BufferUsage.COPY_DST,
    displayUniforms: BufferUsage.UNIFORM | BufferUsage.COPY_DST,
    queues: S | BufferUsage.COPY_SRC | BufferUsage.COPY_DST,
    shadingDispatch: S | BufferUsage.INDIRECT,
    film: S | BufferUsage.COPY_SRC | BufferUsage.COPY_DST,
    filmAovs: S | BufferUsage.COPY_SRC | BufferUsage.COPY_DST,
    filmMoments: S | BufferUsage.COPY_SRC | BufferUsage.COPY_DST,
    filmIds: S | BufferUsage.COPY_SRC | BufferUsage.COPY_DST,
    adaptive: BufferUsage.UNIFORM | BufferUsage.COPY_DST,
    adaptiveError: S | BufferUsage.COPY_SRC,
    adaptivePixels: S | BufferUsage.COPY_SRC | BufferUsage.COPY_DST,
    denoise: BufferUsage.UNIFORM | BufferUsage.COPY_DST,
    denoised: S | BufferUsage.COPY_SRC,
    displayPixels: S | BufferUsage.COPY_SRC,
    timestamps: BufferUsage.QUERY_RESOLVE | BufferUsage.COPY_SRC,
  };
  const resources = {} as Record<PlannedBufferName, GPUBuffer>;
  for (const [name, p] of Object.entries(plan) as [PlannedBufferName, PlannedBuffer][]) {
    const data = uploads[name];
    // The acceleration buffers hold more than the upload: room for any top-level tree, then the
    // bottom levels (written by SceneAcceleration).
    if (name === 'primitives' || name === 'bvhNodes' || name === 'bvhParents') {
      resources[name] = b.create(name, Math.max(p.bytes, data?.byteLength ?? 0), S | BufferUsage.COPY_DST, p.category);
      if (data) device.queue.writeBuffer(resources[name], 0, data);
    } else {
      resources[name] = data ? b.upload(name, data, S, p.category) : b.create(name, p.bytes, usage[name] ?? S, p.category);
    }
  }
  const atlas = uploadTextureAtlas(device, prepared.atlas);
  const environment = uploadEnvironmentTexture(device, lighting.environmentMap);
  device.queue.writeBuffer(resources.lighting, 0, lighting.uniforms);
  const resourceMap: PathTracerResourceMap = {
    ...resources,
    textureAtlas: atlas.view,
    environmentTexture: environment.view,
    display: resources.displayUniforms,
    displayFilm: resources.film,
    displayPixels: resources.displayPixels,
  };
  return { resources, resourceMap, atlasTexture: atlas.texture, environmentTexture: environment.texture, textureBytes: atlas.bytes + environment.bytes };
}

/** The device memory the renderer's buffers (by category) and textures occupy. */
export function rendererMemory(buffers: GpuBufferSet, textureBytes: number): WavefrontMemoryStats {
  const sceneBytes = buffers.bytes('scene') + textureBytes;
  const queueBytes = buffers.bytes('queue');
  const frameBytes = buffers.bytes('frame');
  return { sceneBytes, textureBytes, queueBytes, frameBytes, totalBytes: sceneBytes + queueBytes + frameBytes };
}
