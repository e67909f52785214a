import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { BufferUsage } from '../gpu/webgpu-constants.ts';
import { buildGpuLighting } from '../lighting/gpu-lighting.ts';
import type { WavefrontCameraInput } from '../scene/types.ts';
import { createKernelBindGroups } from './bind-groups.ts';
import type { PlannedBufferName } from './buffer-plan.ts';
import { normalizeWavefrontCamera } from './camera.ts';
import { instanceIdTables } from './instance-ids.ts';
import { assertUsable, resetAccumulation, submittedWork, writeFrameUniforms, type RendererState } from './renderer-state.ts';
import { packGeometryUpdate, type WavefrontGeometryUpdate, type WavefrontGeometryUpdateStats } from './scene/geometry-update.ts';
import { sceneExtent } from './scene/prepare-scene.ts';
import { SceneAcceleration } from './scene/scene-acceleration.ts';
import { prepareSceneUpdate } from './scene-update.ts';
import type { WavefrontSceneUpdate } from './types.ts';

// Changes to a live renderer: the camera, moved geometry, a replaced scene. Each waits for the
// frames requested before it (they render what they were requested with) and restarts the
// accumulation.

/** Uploads or builds the BVH (accelerationBuildMode); called once by the factory. */
export async function createAcceleration(s: RendererState): Promise<void> {
  const r = s.resources;
  s.acceleration = await SceneAcceleration.create(s.device, s.scene.prepared, { primitives: r.primitives, bvhNodes: r.bvhNodes, bvhParents: r.bvhParents }, s.buffers);
}

export async function updateGeometry(s: RendererState, update: WavefrontGeometryUpdate): Promise<WavefrontGeometryUpdateStats> {
  // Frames requested before the update render the geometry they were requested with.
  await submittedWork(s);
  const started = performance.now();
  const p = s.scene.prepared;
  const packed = packGeometryUpdate(s.scene.normalized, p, update);
  const extent = sceneExtent(packed.scene, packed.bounds);
  const lighting = packed.lights
    ? buildGpuLighting({ config: s.config.lighting, triangles: { records: packed.lights.records, count: packed.lights.count }, sceneCenter: extent.sceneCenter, sceneRadius: extent.sceneRadius })
    : s.lighting;
  if (lighting.heap.byteLength > s.resources.lights.size) {
    throw new GpuRendererError('INVALID_STATE', 'the update changes the size of the light tables; create a new renderer for it', { field: 'meshes' });
  }
  const queue = s.device.queue;
  if (packed.vertexStreams) queue.writeBuffer(s.resources.vertexStreams, 0, packed.vertexStreams);
  if (packed.instances) {
    queue.writeBuffer(s.resources.instances, 0, packed.instances);
    p.instances = packed.instances;
  }
  if (packed.lights) {
    queue.writeBuffer(s.resources.lights, 0, lighting.heap);
    queue.writeBuffer(s.resources.lighting, 0, lighting.uniforms);
    s.lighting = lighting;
    p.lights = packed.lights.records;
    p.lightPower = packed.lights.totalPower;
  }
  s.scene.normalized = packed.scene;
  p.sceneCenter = extent.sceneCenter;
  p.sceneRadius = extent.sceneRadius;
  writeFrameUniforms(s);
  if (packed.bottomLevels) p.bottomLevels = packed.bottomLevels;
  const accelerationMs = await s.acceleration!.update(packed.topLevel, packed.bvh, packed.bottomLevels !== null);
  resetAccumulation(s);
  const { patch, flat } = packed.topLevel;
  return {
    bvh: packed.bvh, accelerationMs, totalMs: performance.now() - started,
    topLevel: patch ? 'patched' : 'flattened', topLevelRecordsWritten: patch ? patch.slots.length : flat.count,
  };
}

export function updateCamera(s: RendererState, camera: WavefrontCameraInput): void {
  assertUsable(s);
  // A camera is required here (undefined would silently mean the default camera).
  if (camera === undefined) throw new GpuRendererError('INVALID_OPTION', 'expected a camera object, got undefined', { field: 'camera' });
  const normalized = normalizeWavefrontCamera(camera);
  // Frames requested before the change render with the camera they were requested with.
  void s.submissions.after(() => {
    if (s.destroyed) return;
    s.config = { ...s.config, camera: normalized };
    writeFrameUniforms(s);
    resetAccumulation(s);
  }).catch(() => undefined);
}

export async function updateScene(s: RendererState, update: WavefrontSceneUpdate): Promise<void> {
  // Frames requested before the update render the scene they were requested with.
  await submittedWork(s);
  const next = await prepareSceneUpdate(s.scene.normalized, s.sources, s.config, update, s.device.limits);
  assertUsable(s);
  // Every check passed: from here on nothing throws for the input.
  const p = next.prepared;
  let rebind = false;
  const ensure = (name: PlannedBufferName, bytes: number): GPUBuffer => {
    let buffer = s.resources[name];
    if (buffer.size < bytes) {
      buffer = s.buffers.replace(buffer, name, bytes, BufferUsage.STORAGE | BufferUsage.COPY_DST, 'scene');
      s.resources[name] = buffer;
      s.resourceMap[name] = buffer;
      rebind = true;
    }
    return buffer;
  };
  const write = (name: PlannedBufferName, data: ArrayBuffer | ArrayBufferView): void => {
    const bytes = ArrayBuffer.isView(data) ? data : new Uint8Array(data);
    s.device.queue.writeBuffer(ensure(name, bytes.byteLength), 0, bytes.buffer, bytes.byteOffset, bytes.byteLength);
  };
  // The BVH buffers hold any tree of the new scene (2n - 1 nodes), so later rebuilds fit.
  const gpuBuild = p.acceleration.mode === 'gpu';
  ensure('primitives', next.plan.primitives.bytes);
  ensure('bvhNodes', Math.max(next.plan.bvhNodes.bytes, p.bvhNodes.byteLength));
  ensure('bvhParents', Math.max(next.plan.bvhParents.bytes, p.bvhParents.byteLength));
  if (!gpuBuild) {
    write('primitives', p.primitives);
    write('bvhNodes', p.bvhNodes);
    write('bvhParents', p.bvhParents);
  }
  write('alphaPrimitives', p.alphaPrimitives);
  write('instances', p.instances);
  write('indices', p.indices);
  write('vertexStreams', p.vertexStreams);
  write('lights', next.lighting.heap);
  if (rebind) s.encoderOfWaves.rebind(createKernelBindGroups(s.device, s.kernels, s.resourceMap));
  s.device.queue.writeBuffer(s.resources.lighting, 0, next.lighting.uniforms);
  s.sources = { ...s.sources, lightingOptions: next.lightingOptions };
  s.scene = { instanceCount: next.scene.instances.length, sceneObjectCount: next.scene.sceneObjects.length, prepared: p, normalized: next.scene };
  s.lighting = next.lighting;
  s.config = { ...s.config, lighting: next.lightingConfig, ...(next.camera ? { camera: next.camera } : {}) };
  s.instanceIds = instanceIdTables(next.scene, p);
  // A new tree for the new primitives, in the renderer's build mode (the GPU builds it in 'gpu').
  s.acceleration?.destroy();
  s.acceleration = null;
  const r = s.resources;
  s.acceleration = await SceneAcceleration.create(s.device, p, { primitives: r.primitives, bvhNodes: r.bvhNodes, bvhParents: r.bvhParents }, s.buffers);
  writeFrameUniforms(s);
  resetAccumulation(s);
}
