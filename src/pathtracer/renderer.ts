import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { requireInteger } from '../errors/validate.ts';
import { acquireGpuDevice } from '../gpu/acquire-device.ts';
import { BufferUsage } from '../gpu/webgpu-constants.ts';
import { queueCounterCount } from '../gpu-layout/constants.ts';
import { buildGpuLighting, type GpuLighting } from '../lighting/gpu-lighting.ts';
import { uploadEnvironmentTexture } from '../lighting/upload-environment.ts';
import { uploadTextureAtlas } from '../materials/textures/upload-texture-atlas.ts';
import { normalizeWavefrontScene, type NormalizedScene } from '../scene/normalize-scene.ts';
import type { WavefrontCameraInput } from '../scene/types.ts';
import { allShaderFeatures, type ShaderFeatures } from '../shaders/features.ts';
import { createKernelBindGroups, type PathTracerResourceMap } from './bind-groups.ts';
import { checkBufferLimits, maxWavesPerSubmission, planBuffers, queueCapacity, type BufferPlanInput, type PlannedBuffer, type PlannedBufferName } from './buffer-plan.ts';
import { normalizeWavefrontCamera } from './camera.ts';
import { resolveCanvasTarget } from './canvas-target.ts';
import { createWavefrontPathTracingComputeConfig, type WavefrontPathTracingComputeConfig } from './config.ts';
import { readMeanAov, readMeanRadiance, type AovName } from './film.ts';
import { encodeFrameReadback, frameStatsFromCounters, readFrameReadback, type FrameReadback } from './frame-stats.ts';
import { WavefrontEncoder } from './frame-encoder.ts';
import { GpuBufferSet, readGpuBuffer } from './gpu-buffers.ts';
import { pathTracerPipelines, type PathTracerPipelines } from './pipelines.ts';
import { FilmDisplay } from './presentation.ts';
import { prepareScene, type PreparedScene } from './scene/prepare-scene.ts';
import { vertexStreamBytes } from './scene/pack-vertices.ts';
import { planWaves, tileCount } from './tiling.ts';
import type {
  WavefrontFrameStats,
  WavefrontMemoryStats,
  WavefrontPathTracingOptions,
  WavefrontPathTracingRenderer,
  WavefrontPixelImage,
  WavefrontRadianceImage,
  WavefrontRenderFrameOptions,
  WavefrontRendererSnapshot,
} from './types.ts';
import { packBounceUniforms, packDisplayUniforms, packFrameUniforms, packWaveUniforms } from './uniforms.ts';

/** Sizes known from the validated scene, before the BVH is built: what the first limit check uses. */
function planInput(config: WavefrontPathTracingComputeConfig, scene: NormalizedScene): BufferPlanInput {
  let alpha = 0;
  let lights = 0;
  for (const inst of scene.instances) {
    const material = scene.materials[inst.material ?? scene.meshMaterials[inst.mesh]!]!;
    const triangles = scene.meshes[inst.mesh]!.triangleCount;
    if (material.alphaMode !== 'OPAQUE') alpha += triangles;
    if (material.emission.some((c) => c > 0)) lights += triangles;
  }
  return {
    width: config.width,
    height: config.height,
    tileSize: config.tileSize,
    maxDepth: config.maxDepth,
    aovs: config.aovs,
    ...vertexStreamBytes(scene.meshes),
    primitiveCount: scene.triangleCount + scene.sceneObjects.length,
    alphaPrimitiveCount: alpha,
    instanceCount: scene.instances.length + scene.sceneObjects.length,
    lightCount: lights,
    // Upper bound: a core (7 cells) and four texture bindings (3 cells each) per material.
    materialCells: (scene.materials.length + scene.sceneObjects.length) * 19,
  };
}

/** The shader features a scene needs; everything else is compiled out. */
function sceneFeatures(prepared: PreparedScene, lighting: GpuLighting, config: WavefrontPathTracingComputeConfig): ShaderFeatures {
  return {
    FEATURE_ANALYTIC_SHAPES: prepared.uses.analyticShapes,
    FEATURE_ALPHA_TEST: prepared.uses.alphaTest,
    FEATURE_TEXTURES: prepared.uses.textures,
    FEATURE_EMISSIVE_LIGHTS: prepared.uses.emissiveLights,
    FEATURE_ENVIRONMENT: lighting.uses.environment,
    FEATURE_ENVIRONMENT_MAP: lighting.uses.environmentMap,
    FEATURE_SUN: lighting.uses.sun,
    FEATURE_PORTALS: lighting.uses.portals,
    FEATURE_PUNCTUAL_LIGHTS: lighting.uses.punctualLights,
    FEATURE_AREA_LIGHTS: lighting.uses.areaLights,
    FEATURE_LIGHT_TREE: lighting.uses.lightTree,
    FEATURE_AOVS: config.aovs,
  };
}

/**
 * Creates the wavefront path tracer: validates every option and the scene (typed errors naming the
 * field; nothing is allocated for invalid input), acquires or shares a device, checks every buffer
 * against the device's limits, builds the BVH on the CPU in event-loop-friendly slices, uploads the
 * scene once and compiles the kernels specialised for the scene's features.
 */
export async function createWavefrontPathTracingComputeRenderer(options: WavefrontPathTracingOptions): Promise<WavefrontPathTracingRenderer> {
  const config = createWavefrontPathTracingComputeConfig(options);
  const scene = normalizeWavefrontScene(options);
  const canvas = options.canvas !== undefined ? resolveCanvasTarget(options.canvas) : null;
  const specialization = options.shaderSpecialization ?? 'scene';
  if (specialization !== 'scene' && specialization !== 'off') throw new GpuRendererError('INVALID_OPTION', 'expected "scene" or "off"', { field: 'shaderSpecialization' });
  const acquired = await acquireGpuDevice({
    ...(options.device ? { device: options.device } : {}),
    ...(options.powerPreference ? { powerPreference: options.powerPreference } : {}),
  });
  try {
    const limits = acquired.device.limits;
    const estimate = planInput(config, scene);
    checkBufferLimits(limits, planBuffers(estimate));
    const prepared = await prepareScene(scene, { maxTextureDimension2D: limits.maxTextureDimension2D, maxTextureArrayLayers: limits.maxTextureArrayLayers });
    const lighting = buildGpuLighting({ config: config.lighting, triangles: { records: prepared.lights, count: prepared.lightCount }, sceneCenter: prepared.sceneCenter, sceneRadius: prepared.sceneRadius });
    const plan = planBuffers({ ...estimate, materialCells: prepared.materials.byteLength / 16, lightCount: prepared.lightCount, lightHeapCells: lighting.heap.byteLength / 16, primitiveCount: prepared.primitiveCount });
    checkBufferLimits(limits, plan);
    const features = specialization === 'off' ? allShaderFeatures : sceneFeatures(prepared, lighting, config);
    const pipelines = await pathTracerPipelines(acquired.device, features);
    const renderer = new WavefrontRenderer(acquired, config, scene, prepared, lighting, pipelines, plan);
    if (canvas) await renderer.attachCanvas(canvas);
    return renderer;
  } catch (error) {
    if (acquired.ownsDevice) acquired.device.destroy();
    throw error;
  }
}

class WavefrontRenderer implements WavefrontPathTracingRenderer {
  readonly device: GPUDevice;
  private readonly ownsDevice: boolean;
  private readonly adapter: string;
  private config: WavefrontPathTracingComputeConfig;
  private readonly scene: { instanceCount: number; sceneObjectCount: number; prepared: PreparedScene };
  private readonly capacity: number;
  private readonly buffers: GpuBufferSet;
  private readonly resources: Record<PlannedBufferName, GPUBuffer>;
  private readonly atlasTexture: GPUTexture;
  private readonly environmentTexture: GPUTexture;
  private readonly lighting: GpuLighting;
  private readonly textureBytes: number;
  private readonly encoderOfWaves: WavefrontEncoder;
  private readonly display: FilmDisplay;
  private readonly timing: { querySet: GPUQuerySet; resolve: GPUBuffer } | null;
  private frameCount = 0;
  private samplesAccumulated = 0;
  private destroyed = false;
  private deviceLost = false;
  private deviceLostMessage = '';

  constructor(
    acquired: { device: GPUDevice; ownsDevice: boolean; adapterDescription: string; timestampQueries: boolean },
    config: WavefrontPathTracingComputeConfig,
    scene: NormalizedScene,
    prepared: PreparedScene,
    lighting: GpuLighting,
    pipelines: PathTracerPipelines,
    plan: Record<PlannedBufferName, PlannedBuffer>,
  ) {
    const device = (this.device = acquired.device);
    this.ownsDevice = acquired.ownsDevice;
    this.adapter = acquired.adapterDescription;
    this.config = config;
    this.scene = { instanceCount: scene.instances.length, sceneObjectCount: scene.sceneObjects.length, prepared };
    this.capacity = queueCapacity(config.width, config.height, config.tileSize);
    this.lighting = lighting;
    const b = (this.buffers = new GpuBufferSet(device));
    const S = BufferUsage.STORAGE;
    const uploads: Partial<Record<PlannedBufferName, ArrayBuffer>> = {
      primitives: prepared.primitives,
      bvhNodes: prepared.bvhNodes,
      bvhParents: prepared.bvhParents.buffer as ArrayBuffer,
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
      counters: S | BufferUsage.COPY_SRC | BufferUsage.COPY_DST,
      film: S | BufferUsage.COPY_SRC | BufferUsage.COPY_DST,
      filmAovs: S | BufferUsage.COPY_SRC | BufferUsage.COPY_DST,
      displayPixels: S | BufferUsage.COPY_SRC,
      dispatchArgs: S | BufferUsage.INDIRECT,
      timestamps: BufferUsage.QUERY_RESOLVE | BufferUsage.COPY_SRC,
    };
    const resources = {} as Record<PlannedBufferName, GPUBuffer>;
    for (const [name, p] of Object.entries(plan) as [PlannedBufferName, PlannedBuffer][]) {
      const data = uploads[name];
      resources[name] = data ? b.upload(name, data, S, p.category) : b.create(name, p.bytes, usage[name] ?? S, p.category);
    }
    this.resources = resources;
    const atlas = uploadTextureAtlas(device, prepared.atlas);
    this.atlasTexture = atlas.texture;
    const environment = uploadEnvironmentTexture(device, lighting.environmentMap);
    this.environmentTexture = environment.texture;
    this.textureBytes = atlas.bytes + environment.bytes;
    device.queue.writeBuffer(resources.lighting, 0, lighting.uniforms);
    const map: PathTracerResourceMap = {
      ...resources,
      textureAtlas: atlas.view,
      environmentTexture: environment.view,
      display: resources.displayUniforms,
      displayFilm: resources.film,
      displayPixels: resources.displayPixels,
    };
    this.encoderOfWaves = new WavefrontEncoder(createKernelBindGroups(device, pipelines.kernels, map), resources.dispatchArgs);
    this.display = new FilmDisplay(device, pipelines.resolve, map);
    device.queue.writeBuffer(resources.bounce, 0, packBounceUniforms(config.maxDepth, this.capacity));
    this.writeFrameUniforms();
    this.writeDisplayUniforms();
    this.timing = acquired.timestampQueries ? { querySet: device.createQuerySet({ type: 'timestamp', count: 2 }), resolve: resources.timestamps } : null;
    void device.lost.then((info) => {
      if (this.destroyed) return;
      this.deviceLost = true;
      this.deviceLostMessage = info.message || String(info.reason);
    });
  }

  private writeFrameUniforms(): void {
    const p = this.scene.prepared;
    this.device.queue.writeBuffer(
      this.resources.frame,
      0,
      packFrameUniforms(this.config, {
        lightCount: this.lighting.boundedCount,
        environmentSelectProbability: this.lighting.environmentSelectProbability,
        environmentRadiance: this.lighting.uniformEnvironment,
        sceneCenter: p.sceneCenter,
        sceneRadius: p.sceneRadius,
        queueCapacity: this.capacity,
      }),
    );
  }

  private writeDisplayUniforms(): void {
    const c = this.config;
    this.device.queue.writeBuffer(this.resources.displayUniforms, 0, packDisplayUniforms(c.width, c.height, c.toneMapping, c.exposure));
  }

  async attachCanvas(canvas: Parameters<FilmDisplay['attachCanvas']>[0]): Promise<void> {
    await this.display.attachCanvas(canvas, this.config.width, this.config.height);
  }

  private assertUsable(): void {
    if (this.destroyed) throw new GpuRendererError('RENDERER_DESTROYED', 'the renderer has been destroyed');
    if (this.deviceLost) throw new GpuRendererError('DEVICE_LOST', `the GPU device was lost: ${this.deviceLostMessage}`);
  }

  /** Encodes and submits the waves of `samples` samples per pixel in bounded submissions. */
  private submitFrame(samples: number, readStats: boolean): FrameReadback | null {
    const device = this.device;
    const { width, height, tileSize, maxDepth } = this.config;
    const waves = planWaves(width, height, tileSize, this.samplesAccumulated, samples);
    device.queue.writeBuffer(this.resources.counters, 0, new Uint32Array(queueCounterCount));
    let readback: FrameReadback | null = null;
    for (let first = 0; first < waves.length; first += maxWavesPerSubmission) {
      const batch = waves.slice(first, first + maxWavesPerSubmission);
      const isFirst = first === 0;
      const isLast = first + maxWavesPerSubmission >= waves.length;
      device.queue.writeBuffer(this.resources.wave, 0, packWaveUniforms(batch));
      const encoder = device.createCommandEncoder({ label: 'wavefront frame' });
      const timestampWrites: GPUComputePassTimestampWrites | undefined =
        this.timing && (isFirst || isLast)
          ? { querySet: this.timing.querySet, ...(isFirst ? { beginningOfPassWriteIndex: 0 } : {}), ...(isLast ? { endOfPassWriteIndex: 1 } : {}) }
          : undefined;
      const pass = encoder.beginComputePass(timestampWrites ? { timestampWrites } : {});
      this.encoderOfWaves.encode(pass, batch, maxDepth);
      pass.end();
      if (isLast) {
        if (readStats) readback = encodeFrameReadback(device, encoder, this.resources.counters, this.timing);
        this.display.encodePresent(encoder);
      }
      device.queue.submit([encoder.finish()]);
    }
    this.samplesAccumulated += samples;
    this.frameCount += 1;
    return readback;
  }

  private samplesFor(options: WavefrontRenderFrameOptions | undefined): number {
    if (options === undefined) return this.config.samplesPerPixel;
    if (typeof options !== 'object' || options === null) throw new GpuRendererError('INVALID_OPTION', 'expected an options object', { field: 'options' });
    for (const key of Object.keys(options)) {
      if (key !== 'samplesPerPixel') throw new GpuRendererError('INVALID_OPTION', 'unknown renderFrame option', { field: key });
    }
    if (options.samplesPerPixel === undefined) return this.config.samplesPerPixel;
    return requireInteger(options.samplesPerPixel, 'samplesPerPixel', { min: 1, max: 65536 });
  }

  async renderFrame(options?: WavefrontRenderFrameOptions): Promise<WavefrontFrameStats> {
    this.assertUsable();
    const samples = this.samplesFor(options);
    const started = performance.now();
    const tiles = tileCount(this.config.width, this.config.height, this.config.tileSize);
    const readback = this.submitFrame(samples, true)!;
    let result: { counters: Uint32Array; gpuTimeMs: number | null };
    try {
      result = await readFrameReadback(readback);
    } catch (error) {
      this.assertUsable();
      throw error;
    }
    return frameStatsFromCounters(result.counters, {
      frame: this.frameCount,
      samplesAdded: samples,
      samplesAccumulated: this.samplesAccumulated,
      gpuTimeMs: result.gpuTimeMs,
      wallTimeMs: performance.now() - started,
      memory: this.memory(),
      tiles,
      waves: tiles * samples,
    });
  }

  renderOnce(options?: WavefrontRenderFrameOptions): void {
    this.assertUsable();
    this.submitFrame(this.samplesFor(options), false);
  }

  updateCamera(camera: WavefrontCameraInput): void {
    this.assertUsable();
    this.config = { ...this.config, camera: normalizeWavefrontCamera(camera) };
    this.writeFrameUniforms();
    this.resetAccumulation();
  }

  private resetAccumulation(): void {
    const encoder = this.device.createCommandEncoder();
    encoder.clearBuffer(this.resources.film);
    encoder.clearBuffer(this.resources.filmAovs);
    this.device.queue.submit([encoder.finish()]);
    this.samplesAccumulated = 0;
    this.frameCount = 0;
  }

  async readRadiance(): Promise<WavefrontRadianceImage> {
    this.assertUsable();
    return readMeanRadiance(this.device, this.resources.film, this.config.width, this.config.height);
  }

  async readAov(name: AovName): Promise<WavefrontRadianceImage> {
    this.assertUsable();
    if (name !== 'albedo' && name !== 'normal' && name !== 'depth') throw new GpuRendererError('INVALID_OPTION', `unknown AOV ${JSON.stringify(name)} (albedo, normal, depth)`, { field: 'name' });
    if (!this.config.aovs) throw new GpuRendererError('INVALID_STATE', 'AOVs were not enabled: create the renderer with aovs: true', { field: 'aovs' });
    return readMeanAov(this.device, this.resources.film, this.resources.filmAovs, name, this.config.width, this.config.height);
  }

  async readPixels(): Promise<WavefrontPixelImage> {
    this.assertUsable();
    const { width, height } = this.config;
    const encoder = this.device.createCommandEncoder();
    this.display.encodeResolve(encoder, width, height);
    this.device.queue.submit([encoder.finish()]);
    const bytes = await readGpuBuffer(this.device, this.resources.displayPixels, width * height * 4);
    return { width, height, data: new Uint8ClampedArray(bytes) };
  }

  private memory(): WavefrontMemoryStats {
    const sceneBytes = this.buffers.bytes('scene') + this.textureBytes;
    const queueBytes = this.buffers.bytes('queue');
    const frameBytes = this.buffers.bytes('frame');
    return { sceneBytes, textureBytes: this.textureBytes, queueBytes, frameBytes, totalBytes: sceneBytes + queueBytes + frameBytes };
  }

  getSnapshot(): WavefrontRendererSnapshot {
    const p = this.scene.prepared;
    return {
      width: this.config.width,
      height: this.config.height,
      frame: this.frameCount,
      samplesAccumulated: this.samplesAccumulated,
      maxDepth: this.config.maxDepth,
      samplesPerPixel: this.config.samplesPerPixel,
      tileSize: this.config.tileSize,
      triangleCount: p.triangleCount,
      bvhNodeCount: p.bvh.nodeCount,
      bvhDepth: p.bvh.depth,
      lightCount: this.lighting.boundedCount + this.lighting.directionalCount,
      sceneObjectCount: this.scene.sceneObjectCount,
      instanceCount: this.scene.instanceCount,
      textureCount: p.atlas.textureCount,
      warnings: p.warnings,
      adapter: this.adapter,
      memory: this.memory(),
      destroyed: this.destroyed,
      deviceLost: this.deviceLost,
    };
  }

  destroy(): void {
    if (this.destroyed) return;
    this.destroyed = true;
    this.display.detach();
    this.timing?.querySet.destroy();
    this.buffers.destroy();
    this.atlasTexture.destroy();
    this.environmentTexture.destroy();
    if (this.ownsDevice) this.device.destroy();
  }
}
