import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { acquireGpuDevice } from '../gpu/acquire-device.ts';
import { BufferUsage } from '../gpu/webgpu-constants.ts';
import { queueCounterCount, queueCounterSlots, rendererWavefrontComputeWorkgroupSize } from '../gpu-layout/constants.ts';
import { instanceLayout } from '../gpu-layout/records.ts';
import { fieldOf } from '../gpu-layout/struct-layout.ts';
import { buildGpuLighting, type GpuLighting } from '../lighting/gpu-lighting.ts';
import { uploadEnvironmentTexture } from '../lighting/upload-environment.ts';
import { uploadTextureAtlas } from '../materials/textures/upload-texture-atlas.ts';
import { isWavefrontAovName, wavefrontAovNames, type WavefrontAovName } from '../film/aovs.ts';
import { normalizeWavefrontScene, type NormalizedScene } from '../scene/normalize-scene.ts';
import type { WavefrontCameraInput } from '../scene/types.ts';
import { allShaderFeatures } from '../shaders/features.ts';
import { createKernelBindGroups, type PathTracerResourceMap } from './bind-groups.ts';
import { checkBufferLimits, planBuffers, waveBufferBytes, type PlannedBuffer, type PlannedBufferName } from './buffer-plan.ts';
import { normalizeWavefrontCamera } from './camera.ts';
import { resolveCanvasTarget } from '../film/display/canvas-target.ts';
import { createWavefrontPathTracingComputeConfig, type WavefrontPathTracingComputeConfig } from './config.ts';
import { instanceMaterial } from './scene/flatten-primitives.ts';
import { AdaptiveScheduler, createAdaptivePipelines } from '../film/adaptive/scheduler.ts';
import type { WavefrontDenoiser, WavefrontDenoiserFactory } from '../film/denoise/denoiser.ts';
import { prepareWavefrontDenoiser, resolveWavefrontDenoiser } from '../film/denoise/registry.ts';
import { DispatchTally } from './dispatch-tally.ts';
import { readAovImage, readMeanRadiance, readRgbaImage, type InstanceIds } from '../film/accumulation/readback.ts';
import { FrameReadbackRing, frameStatsFromCounters, type FrameReadout } from './frame-stats.ts';
import { parseRenderFrameOptions, type ParsedFrameOptions } from './output-options.ts';
import type { WavefrontOutputState, WavefrontRenderProgress } from './output-types.ts';
import { WavefrontEncoder } from './frame-encoder.ts';
import { GpuBufferSet, readGpuBuffer } from './gpu-buffers.ts';
import { checkIntegratorLimits, pathTracerPipelines, type PathTracerPipelines } from './pipelines.ts';
import { FilmDisplay } from '../film/display/film-display.ts';
import { prepareGeometry, prepareMaterials, sceneExtent, type PreparedScene } from './scene/prepare-scene.ts';
import { SceneAcceleration } from './scene/scene-acceleration.ts';
import { packGeometryUpdate, type WavefrontGeometryUpdate, type WavefrontGeometryUpdateStats } from './scene/geometry-update.ts';
import { lightingOptionsOf, prepareSceneUpdate, type SceneSources } from './scene-update.ts';
import { planInput, sceneFeatures } from './scene-plan.ts';
import { planFrameWaves, planListWaves, type Wave } from './waves.ts';
import { deviceWavePaths, gridWorkgroupLimit, waveBound } from './wave-capacity.ts';
import type {
  WavefrontFrameStats,
  WavefrontMemoryStats,
  WavefrontPathTracingOptions,
  WavefrontPathTracingRenderer,
  WavefrontPixelImage,
  WavefrontRadianceImage,
  WavefrontRenderFrameOptions,
  WavefrontRendererSnapshot,
  WavefrontSceneUpdate,
} from './types.ts';
import { packBounceUniforms, packDisplayUniforms, packFrameUniforms, packWaveUniforms } from './uniforms.ts';

/**
 * Object id (the packed instance record's objectId: the instance's numeric id, else its index) and
 * material index of every instance record, for the id AOVs.
 */
function instanceIdTables(scene: NormalizedScene, prepared: PreparedScene): InstanceIds {
  const count = scene.instances.length + scene.sceneObjects.length;
  const objectIds = new Int32Array(count);
  const materialIds = new Int32Array(count);
  const view = new DataView(prepared.instances);
  const objectIdOffset = fieldOf(instanceLayout, 'objectId').offset;
  for (let i = 0; i < count; i++) objectIds[i] = view.getUint32(i * instanceLayout.size + objectIdOffset, true);
  scene.instances.forEach((inst, i) => (materialIds[i] = instanceMaterial(scene, inst)));
  // Analytic scene objects own their materials, numbered after the scene's.
  scene.sceneObjects.forEach((_, k) => (materialIds[scene.instances.length + k] = scene.materials.length + k));
  return { objectIds, materialIds };
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
    ...(options.device !== undefined ? { device: options.device } : {}),
    ...(options.powerPreference !== undefined ? { powerPreference: options.powerPreference } : {}),
  });
  try {
    resolveWavefrontDenoiser(config.output, acquired.device);
    checkIntegratorLimits(config.integrator, acquired.device.limits);
    const limits = acquired.device.limits;
    // Buffers are checked at the largest wave this renderer may grow to; they start at the work of
    // one call of samplesPerPixel and grow when a frame asks for more (growQueues).
    const maxWavePaths = waveBound(deviceWavePaths(limits), config.tileSize);
    const estimate = planInput(config, scene, maxWavePaths);
    checkBufferLimits(limits, planBuffers(estimate));
    const materials = prepareMaterials(scene, { maxTextureDimension2D: limits.maxTextureDimension2D, maxTextureArrayLayers: limits.maxTextureArrayLayers }, { energyCompensation: config.energyCompensation });
    const prepared = await prepareGeometry(scene, materials, { accelerationBuildMode: config.accelerationBuildMode });
    const lighting = buildGpuLighting({ config: config.lighting, triangles: { records: prepared.lights, count: prepared.lightCount }, sceneCenter: prepared.sceneCenter, sceneRadius: prepared.sceneRadius });
    const plan = planBuffers({ ...estimate, materialCells: prepared.materials.byteLength / 16, lightCount: prepared.lightCount, lightHeapCells: lighting.heap.byteLength / 16, primitiveCount: prepared.primitiveCount });
    checkBufferLimits(limits, plan);
    const wavePaths = Math.min(maxWavePaths, config.width * config.height * config.samplesPerPixel);
    const initialPlan = planBuffers({ ...estimate, materialCells: prepared.materials.byteLength / 16, lightCount: prepared.lightCount, lightHeapCells: lighting.heap.byteLength / 16, primitiveCount: prepared.primitiveCount, wavePaths });
    const features = specialization === 'off' ? allShaderFeatures : sceneFeatures(prepared, lighting, config);
    const [pipelines, adaptivePipelines, denoisePipelines] = await Promise.all([
      pathTracerPipelines(acquired.device, features, config.integrator),
      config.output.adaptive ? createAdaptivePipelines(acquired.device, features) : null,
      config.output.denoise ? prepareWavefrontDenoiser(acquired.device, config.output.denoise, config.output.denoiseWeights, features) : null,
    ]);
    const sources: SceneSources = { materials, features, lightingOptions: lightingOptionsOf(options) };
    const renderer = new WavefrontRenderer(acquired, config, scene, sources, prepared, lighting, { ...pipelines, adaptive: adaptivePipelines, denoise: denoisePipelines }, initialPlan, { wavePaths, maxWavePaths });
    try {
      await renderer.createAcceleration();
    } catch (error) {
      renderer.destroy();
      throw error;
    }
    if (canvas) await renderer.attachCanvas(canvas);
    return renderer;
  } catch (error) {
    if (acquired.ownsDevice) acquired.device.destroy();
    throw error;
  }
}

/** Samples per adaptive-sampling step: the convergence test runs (and its count is read) between steps. */
export const adaptiveStepSamples = 4;

type RendererPipelines = PathTracerPipelines & {
  adaptive: Awaited<ReturnType<typeof createAdaptivePipelines>> | null;
  denoise: WavefrontDenoiserFactory | null;
};

/** What one frame's passes produced, before the statistics are read back. */
interface FrameOutcome {
  samplesAdded: number;
  waves: number;
  /** Paths per wave when the frame's last wave was encoded. */
  wavePaths: number;
  submissions: number;
  tally: DispatchTally;
  pixelSamples: number;
}

class WavefrontRenderer extends EventTarget implements WavefrontPathTracingRenderer {
  readonly device: GPUDevice;
  private readonly ownsDevice: boolean;
  private readonly adapter: string;
  private config: WavefrontPathTracingComputeConfig;
  private scene: { instanceCount: number; sceneObjectCount: number; prepared: PreparedScene; normalized: NormalizedScene };
  /** What updateScene rebuilds geometry from: the packed materials, the compiled features, the lighting options. */
  private sources: SceneSources;
  private readonly kernels: PathTracerPipelines['kernels'];
  /** The BVH on the device (build mode, refit and rebuild for geometry updates). */
  private acceleration: SceneAcceleration | null = null;
  /** Paths per wave the queue buffers hold now, and the most they may grow to. */
  private capacity: number;
  private readonly maxWavePaths: number;
  private readonly buffers: GpuBufferSet;
  private readonly resources: Record<PlannedBufferName, GPUBuffer>;
  private readonly resourceMap: PathTracerResourceMap;
  private readonly atlasTexture: GPUTexture;
  private readonly environmentTexture: GPUTexture;
  private lighting: GpuLighting;
  private readonly textureBytes: number;
  private readonly encoderOfWaves: WavefrontEncoder;
  private readonly display: FilmDisplay;
  private readonly readbacks: FrameReadbackRing;
  /** Submission phases of renderFrame / renderOnce calls run one at a time, in call order. */
  private submissions: Promise<unknown> = Promise.resolve();
  private queuedSubmissions = 0;
  private readonly adaptive: AdaptiveScheduler | null;
  private readonly denoiser: WavefrontDenoiser | null;
  private instanceIds: InstanceIds;
  private frameCount = 0;
  private samplesAccumulated = 0;
  /** Pixel samples in the accumulation (differs from pixels x samplesAccumulated with adaptive sampling). */
  private pixelSamplesAccumulated = 0;
  /** Whether `denoised` holds the denoiser's output for the current accumulation. */
  private denoisedFresh = false;
  private destroyed = false;
  private deviceLost = false;
  private deviceLostMessage = '';

  constructor(
    acquired: { device: GPUDevice; ownsDevice: boolean; adapterDescription: string; timestampQueries: boolean; softwareAdapter: boolean },
    config: WavefrontPathTracingComputeConfig,
    scene: NormalizedScene,
    sources: SceneSources,
    prepared: PreparedScene,
    lighting: GpuLighting,
    pipelines: RendererPipelines,
    plan: Record<PlannedBufferName, PlannedBuffer>,
    waves: { wavePaths: number; maxWavePaths: number },
  ) {
    super();
    const device = (this.device = acquired.device);
    this.ownsDevice = acquired.ownsDevice;
    this.adapter = acquired.adapterDescription;
    this.config = config;
    this.sources = sources;
    this.kernels = pipelines.kernels;
    this.scene = { instanceCount: scene.instances.length, sceneObjectCount: scene.sceneObjects.length, prepared, normalized: scene };
    this.capacity = waves.wavePaths;
    this.maxWavePaths = waves.maxWavePaths;
    this.lighting = lighting;
    const b = (this.buffers = new GpuBufferSet(device));
    const S = BufferUsage.STORAGE;
    // The BVH buffers hold any tree of the scene (2n - 1 nodes), so a rebuild fits; in 'gpu' mode the
    // GPU build fills them (scene-acceleration.ts).
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
      if (name === 'bvhNodes' || name === 'bvhParents') {
        resources[name] = b.create(name, Math.max(p.bytes, data?.byteLength ?? 0), S | BufferUsage.COPY_DST, p.category);
        if (data) device.queue.writeBuffer(resources[name], 0, data);
      } else {
        resources[name] = data ? b.upload(name, data, S, p.category) : b.create(name, p.bytes, usage[name] ?? S, p.category);
      }
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
    this.resourceMap = map;
    this.encoderOfWaves = new WavefrontEncoder(createKernelBindGroups(device, pipelines.kernels, map), config.width * config.height, gridWorkgroupLimit(acquired.softwareAdapter, device.limits), config.integrator);
    const out = config.output;
    this.display = new FilmDisplay(device, pipelines.resolve, map, out.denoise ? resources.denoised : undefined);
    if (out.denoise?.present === 'denoised') this.display.source = 'denoised';
    this.adaptive = out.adaptive && pipelines.adaptive ? new AdaptiveScheduler(device, pipelines.adaptive, map, out.adaptive, config.width, config.height) : null;
    this.denoiser = pipelines.denoise?.create({ device, width: config.width, height: config.height, resources: map, createBuffer: (label, size, usage) => b.create(label, size, usage, 'frame') }) ?? null;
    this.adaptive?.reset();
    this.instanceIds = instanceIdTables(scene, prepared);
    device.queue.writeBuffer(resources.bounce, 0, packBounceUniforms(config.maxDepth, this.capacity));
    this.writeFrameUniforms();
    this.writeDisplayUniforms();
    const slots = config.framesInFlight;
    this.readbacks = new FrameReadbackRing(device, slots, acquired.timestampQueries ? { querySet: device.createQuerySet({ type: 'timestamp', count: 2 * slots }), resolve: resources.timestamps } : null);
    void device.lost.then((info) => {
      if (this.destroyed) return;
      this.deviceLost = true;
      this.deviceLostMessage = info.message || String(info.reason);
    });
  }

  /** Uploads or builds the BVH (accelerationBuildMode); called once by the factory. */
  async createAcceleration(): Promise<void> {
    const r = this.resources;
    this.acceleration = await SceneAcceleration.create(this.device, this.scene.prepared, { primitives: r.primitives, bvhNodes: r.bvhNodes, bvhParents: r.bvhParents }, this.buffers);
  }

  async updateGeometry(update: WavefrontGeometryUpdate): Promise<WavefrontGeometryUpdateStats> {
    // Frames requested before the update render the geometry they were requested with.
    await this.submittedWork();
    const started = performance.now();
    const p = this.scene.prepared;
    const packed = packGeometryUpdate(this.scene.normalized, p, update);
    const extent = sceneExtent(packed.scene, packed.flat);
    const lighting = packed.lights
      ? buildGpuLighting({ config: this.config.lighting, triangles: { records: packed.lights.records, count: packed.lights.count }, sceneCenter: extent.sceneCenter, sceneRadius: extent.sceneRadius })
      : this.lighting;
    if (lighting.heap.byteLength > this.resources.lights.size) {
      throw new GpuRendererError('INVALID_STATE', 'the update changes the size of the light tables; create a new renderer for it', { field: 'meshes' });
    }
    const queue = this.device.queue;
    if (packed.vertexStreams) queue.writeBuffer(this.resources.vertexStreams, 0, packed.vertexStreams);
    if (packed.instances) {
      queue.writeBuffer(this.resources.instances, 0, packed.instances);
      p.instances = packed.instances;
    }
    if (packed.lights) {
      queue.writeBuffer(this.resources.lights, 0, lighting.heap);
      queue.writeBuffer(this.resources.lighting, 0, lighting.uniforms);
      this.lighting = lighting;
      p.lights = packed.lights.records;
      p.lightPower = packed.lights.totalPower;
    }
    this.scene.normalized = packed.scene;
    p.sceneCenter = extent.sceneCenter;
    p.sceneRadius = extent.sceneRadius;
    this.writeFrameUniforms();
    const accelerationMs = await this.acceleration!.update(packed.flat, packed.bvh);
    this.resetAccumulation();
    return { bvh: packed.bvh, accelerationMs, totalMs: performance.now() - started };
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
    const exposure = c.exposure * 2 ** c.output.exposureEv;
    this.device.queue.writeBuffer(this.resources.displayUniforms, 0, packDisplayUniforms(c.width, c.height, c.toneMapping, exposure, c.output.presentationOutput));
    // The noise threshold applies to the image as displayed (Cycles multiplies by the film exposure).
    this.adaptive?.writeUniforms(c.width, c.height, exposure);
  }

  async attachCanvas(canvas: Parameters<FilmDisplay['attachCanvas']>[0]): Promise<void> {
    await this.display.attachCanvas(canvas, this.config.width, this.config.height);
  }

  private assertUsable(): void {
    if (this.destroyed) throw new GpuRendererError('RENDERER_DESTROYED', 'the renderer has been destroyed');
    if (this.deviceLost) throw new GpuRendererError('DEVICE_LOST', `the GPU device was lost: ${this.deviceLostMessage}`);
  }

  /**
   * Runs a submission phase (a frame's encoding and submits) after every earlier one: renderFrame
   * and renderOnce calls reach the GPU in call order even when a caller does not await them, and
   * reads and camera changes see all the work requested before them. Runs `phase` at once (in the
   * caller's turn) when nothing is queued.
   */
  private afterSubmissions<T>(phase: () => T | Promise<T>): Promise<T> {
    const run = this.queuedSubmissions === 0 ? new Promise<T>((resolve) => resolve(phase())) : this.submissions.then(phase);
    this.queuedSubmissions += 1;
    const settled = run.then(
      () => undefined,
      () => undefined,
    );
    this.submissions = settled.then(() => {
      this.queuedSubmissions -= 1;
    });
    return run;
  }

  /**
   * Encodes waves into command buffers of at most maxFramePassesPerSubmission waves each and submits
   * them; the GPU timestamps of readback slot `slot` bracket the frame (begin at its first pass, end
   * at every batch's last, so the last write wins). Returns the number of submissions.
   */
  private submitWaves(waves: readonly Wave[], firstOfFrame: boolean, slot: number | null): number {
    const device = this.device;
    const perSubmission = this.config.output.maxFramePassesPerSubmission;
    let submissions = 0;
    for (let first = 0; first < waves.length; first += perSubmission) {
      const batch = waves.slice(first, first + perSubmission);
      device.queue.writeBuffer(this.resources.wave, 0, packWaveUniforms(batch));
      const encoder = device.createCommandEncoder({ label: 'wavefront frame' });
      const timestampWrites = slot === null ? undefined : this.readbacks.timestampWrites(slot, firstOfFrame && first === 0);
      const pass = encoder.beginComputePass(timestampWrites ? { timestampWrites } : {});
      this.encoderOfWaves.encode(pass, batch, this.config.maxDepth);
      pass.end();
      device.queue.submit([encoder.finish()]);
      submissions += 1;
    }
    return submissions;
  }

  /**
   * Grows the wave buffers (path records, queues) to hold waves of `paths` paths, up to the
   * renderer's bound, so a frame of more samples than the renderer was created with still takes
   * device-sized waves. Work already submitted keeps the old buffers until it completes.
   */
  private growQueues(paths: number): void {
    const wanted = Math.min(paths, this.maxWavePaths);
    if (wanted <= this.capacity) return;
    const bytes = waveBufferBytes(wanted);
    const usage = BufferUsage.STORAGE | BufferUsage.COPY_SRC | BufferUsage.COPY_DST;
    const old = { paths: this.resources.paths, queues: this.resources.queues };
    for (const name of ['paths', 'queues'] as const) {
      this.resources[name] = this.resourceMap[name] = this.buffers.create(name, bytes[name], usage, 'queue');
    }
    // The frame's statistics so far move with the queues (a frame may grow between its steps).
    const encoder = this.device.createCommandEncoder({ label: 'wave buffers' });
    encoder.copyBufferToBuffer(old.queues, 0, this.resources.queues, 0, queueCounterCount * 4);
    this.device.queue.submit([encoder.finish()]);
    this.buffers.release(old.paths);
    this.buffers.release(old.queues);
    this.capacity = wanted;
    this.encoderOfWaves.rebind(createKernelBindGroups(this.device, this.kernels, this.resourceMap));
    this.device.queue.writeBuffer(this.resources.bounce, 0, packBounceUniforms(this.config.maxDepth, this.capacity));
    this.writeFrameUniforms();
  }

  private emitProgress(progress: WavefrontRenderProgress, listener: ((p: WavefrontRenderProgress) => void) | null): void {
    this.config.output.onProgress?.(progress);
    listener?.(progress);
    this.dispatchEvent(new CustomEvent('progress', { detail: progress }));
  }

  /** Starts a frame: zeroed statistics, a fresh dispatch tally, the denoised copy out of date. */
  private beginFrame(): FrameOutcome {
    const tally = new DispatchTally();
    this.encoderOfWaves.tally = tally;
    this.device.queue.writeBuffer(this.resources.queues, 0, new Uint32Array(queueCounterCount));
    this.denoisedFresh = false;
    return { samplesAdded: 0, waves: 0, wavePaths: this.capacity, submissions: 0, tally, pixelSamples: 0 };
  }

  /**
   * Submits `step` sample passes: full-frame waves over pixels x step samples, or list waves over
   * the pixels adaptive sampling last counted as active, then (adaptive) the convergence test, whose
   * list length comes back through the returned promise.
   */
  private submitStep(outcome: FrameOutcome, step: number, slot: number | null): Promise<unknown> | null {
    const pixels = this.config.width * this.config.height;
    const adaptive = this.adaptive;
    const active = adaptive ? adaptive.counts.activePixels : pixels;
    this.growQueues(active * step);
    const waves = adaptive ? planListWaves(active, this.capacity, step) : planFrameWaves(pixels, this.capacity, this.samplesAccumulated + outcome.samplesAdded, step);
    outcome.submissions += this.submitWaves(waves, outcome.samplesAdded === 0, slot);
    outcome.waves += waves.length;
    outcome.wavePaths = this.capacity;
    outcome.samplesAdded += step;
    outcome.pixelSamples += step * active;
    if (!adaptive) return null;
    const encoder = this.device.createCommandEncoder({ label: 'adaptive sampling' });
    const staging = adaptive.encodeConvergence(encoder, outcome.tally);
    this.device.queue.submit([encoder.finish()]);
    outcome.submissions += 1;
    return adaptive.read(staging);
  }

  private endFrame(outcome: FrameOutcome): void {
    this.encoderOfWaves.tally = null;
    this.samplesAccumulated += outcome.samplesAdded;
    this.pixelSamplesAccumulated += outcome.pixelSamples;
    this.frameCount += 1;
  }

  /**
   * Submits a frame's sample passes. Without adaptive sampling or a budget: one group of waves,
   * nothing waited for. With adaptive sampling: steps of adaptiveStepSamples passes over the active
   * list, each followed by the convergence test; each step is sized by the list length of the step
   * before the previous one, so the GPU always has the next step queued while the CPU waits for a
   * count (the waves bound themselves by the GPU's own count; a pixel a stale count leaves out waits
   * a step). With a budget: the guaranteed passes, then one pass at a time while the measured pass
   * time fits (waiting for the GPU between passes).
   */
  private async renderPasses(frame: ParsedFrameOptions, started: number, slot: number): Promise<FrameOutcome> {
    const outcome = this.beginFrame();
    const adaptive = this.adaptive;
    let pendingCount: Promise<unknown> | null = null;
    while (outcome.samplesAdded < frame.ceiling) {
      if (adaptive && adaptive.counts.activePixels === 0) break;
      const rendered = outcome.samplesAdded;
      let step = frame.ceiling - rendered;
      if (frame.budgetMs !== null) step = rendered < frame.minimum ? frame.minimum - rendered : 1;
      if (adaptive) step = Math.min(step, adaptiveStepSamples);
      const counted = this.submitStep(outcome, step, slot);
      const more = outcome.samplesAdded < frame.ceiling;
      if (counted) {
        if (pendingCount) await pendingCount;
        pendingCount = counted;
      } else if (more && frame.budgetMs !== null) {
        await this.device.queue.onSubmittedWorkDone();
      }
      if (!more) break;
      const elapsedMs = performance.now() - started;
      const perPassMs = elapsedMs / outcome.samplesAdded;
      if (frame.budgetMs !== null && outcome.samplesAdded >= frame.minimum && elapsedMs + perPassMs > frame.budgetMs) break;
      this.emitProgress(this.progressOf(frame, outcome, elapsedMs, false), frame.onProgress);
    }
    if (pendingCount) await pendingCount;
    this.endFrame(outcome);
    return outcome;
  }

  private progressOf(frame: ParsedFrameOptions, outcome: FrameOutcome, elapsedMs: number, done: boolean, frameNumber = this.frameCount + (done ? 0 : 1), accumulated = this.samplesAccumulated + (done ? 0 : outcome.samplesAdded)): WavefrontRenderProgress {
    const pixels = this.config.width * this.config.height;
    const counts = this.adaptive?.counts ?? null;
    let remaining = 0;
    if (!done && outcome.samplesAdded > 0) {
      const perPass = elapsedMs / outcome.samplesAdded;
      remaining = (frame.ceiling - outcome.samplesAdded) * perPass;
      if (counts && outcome.pixelSamples > 0) {
        // Adaptive frames end when every pixel converged: the predicted pixel samples at the measured rate.
        remaining = Math.min(remaining, (counts.estimatedRemainingPixelSamples * elapsedMs) / outcome.pixelSamples);
      }
      if (frame.budgetMs !== null) remaining = Math.min(remaining, Math.max(0, frame.budgetMs - elapsedMs));
    }
    return {
      frame: frameNumber,
      samplesThisFrame: outcome.samplesAdded,
      targetSamplesThisFrame: frame.ceiling,
      samplesAccumulated: accumulated,
      activePixels: counts ? counts.activePixels : pixels,
      totalPixels: pixels,
      elapsedMs,
      estimatedRemainingMs: remaining,
      estimatedTotalMs: elapsedMs + remaining,
      estimatedRemainingPixelSamples: counts ? counts.estimatedRemainingPixelSamples : null,
      done,
    };
  }

  /** Denoises the accumulation into `denoised` (in `encoder`) unless it is current. */
  private encodeDenoise(encoder: GPUCommandEncoder, tally: DispatchTally | null): boolean {
    if (!this.denoiser || this.denoisedFresh) return false;
    this.denoiser.encode(encoder, tally);
    this.denoisedFresh = true;
    return true;
  }

  /** The frame's closing submission: denoising when the canvas shows it, the statistics copy into `slot`, the present. */
  private finishFrame(tally: DispatchTally, slot: number | null): boolean {
    const encoder = this.device.createCommandEncoder({ label: 'frame end' });
    const denoised = this.display.hasCanvas && this.display.source === 'denoised' ? this.encodeDenoise(encoder, tally) : false;
    if (slot !== null) this.readbacks.encodeCopy(encoder, slot, this.resources.queues);
    this.display.encodePresent(encoder);
    this.device.queue.submit([encoder.finish()]);
    return denoised;
  }

  private outputState(): WavefrontOutputState {
    const o = this.config.output;
    return {
      maxFramePassesPerSubmission: o.maxFramePassesPerSubmission,
      presentationOutput: o.presentationOutput,
      exposureEv: o.exposureEv,
      adaptiveSampling: o.adaptive,
      denoise: o.denoise,
      featureFlags: o.features.featureFlags,
      transportExperiments: o.features.transportExperiments,
      transportExperimentFlags: o.features.transportExperimentFlags,
      transportExperimentRequestedFlags: o.features.transportExperimentRequestedFlags,
    };
  }

  /**
   * Submits the frame as soon as fewer than framesInFlight frames await their statistics, and
   * resolves to its statistics once they come back (through the readback ring). A caller that
   * requests the next frame before awaiting this one keeps the GPU fed: nothing between two
   * submissions waits for the GPU.
   */
  async renderFrame(options?: WavefrontRenderFrameOptions): Promise<WavefrontFrameStats> {
    this.assertUsable();
    const frame = parseRenderFrameOptions(options, this.config.samplesPerPixel);
    const started = performance.now();
    let submitted: { outcome: FrameOutcome; denoised: boolean; frameNumber: number; samplesAccumulated: number; memory: WavefrontMemoryStats; readout: Promise<FrameReadout> };
    let readout: FrameReadout;
    try {
      submitted = await this.afterSubmissions(async () => {
        const slot = await this.readbacks.acquire();
        this.assertUsable();
        const outcome = await this.renderPasses(frame, started, slot);
        const denoised = this.finishFrame(outcome.tally, slot);
        outcome.submissions += 1;
        return { outcome, denoised, frameNumber: this.frameCount, samplesAccumulated: this.samplesAccumulated, memory: this.memory(), readout: this.readbacks.read(slot) };
      });
      readout = await submitted.readout;
    } catch (error) {
      this.assertUsable();
      throw error;
    }
    const { outcome } = submitted;
    const wallTimeMs = performance.now() - started;
    const pixels = this.config.width * this.config.height;
    // The camera-ray counter is exact where the CPU's step accounting used a stale list length.
    const cameraRays = readout.counters[queueCounterSlots.cameraRays]!;
    this.pixelSamplesAccumulated += cameraRays - outcome.pixelSamples;
    outcome.pixelSamples = cameraRays;
    const settings = this.config.output.adaptive;
    const counts = this.adaptive?.counts;
    const stats = frameStatsFromCounters(readout.counters, {
      frame: submitted.frameNumber,
      samplesAdded: outcome.samplesAdded,
      samplesAccumulated: submitted.samplesAccumulated,
      samplesPerPixel: frame.ceiling,
      frameTimeBudgetMs: frame.budgetMs,
      gpuTimeMs: readout.gpuTimeMs,
      wallTimeMs,
      memory: submitted.memory,
      tiles: Math.ceil(pixels / outcome.wavePaths),
      waves: outcome.waves,
      wavePaths: outcome.wavePaths,
      submissions: outcome.submissions,
      deviceLost: this.deviceLost,
      gpuParallelism: outcome.tally.report(this.device.limits, rendererWavefrontComputeWorkgroupSize),
      adaptive:
        settings && counts
          ? {
            threshold: settings.threshold,
            minimumSamplesPerPixel: settings.minimumSamplesPerPixel,
            activePixels: counts.activePixels,
            convergedPixels: pixels - counts.activePixels,
            pixelSamples: outcome.pixelSamples,
            meanSamplesPerPixel: this.pixelSamplesAccumulated / pixels,
            estimatedRemainingPixelSamples: counts.estimatedRemainingPixelSamples,
          }
          : null,
      denoised: submitted.denoised,
      output: this.outputState(),
    });
    this.emitProgress(this.progressOf(frame, outcome, wallTimeMs, true, submitted.frameNumber, submitted.samplesAccumulated), frame.onProgress);
    return stats;
  }

  renderOnce(options?: WavefrontRenderFrameOptions): void {
    this.assertUsable();
    const frame = parseRenderFrameOptions(options, this.config.samplesPerPixel);
    if (frame.budgetMs !== null) throw new GpuRendererError('INVALID_OPTION', 'a frame time budget needs renderFrame, which waits for the GPU', { field: 'frameTimeBudgetMs' });
    void this.afterSubmissions(() => {
      if (this.destroyed || this.deviceLost) return;
      const outcome = this.beginFrame();
      // One step of all the passes; adaptive sampling's count lands when the GPU gets there and sizes
      // a later frame (nothing here waits for it).
      if (!(this.adaptive && this.adaptive.counts.activePixels === 0)) void this.submitStep(outcome, frame.ceiling, null)?.catch(() => undefined);
      this.endFrame(outcome);
      this.finishFrame(outcome.tally, null);
    }).catch(() => undefined);
  }

  updateCamera(camera: WavefrontCameraInput): void {
    this.assertUsable();
    // A camera is required here (undefined would silently mean the default camera).
    if (camera === undefined) throw new GpuRendererError('INVALID_OPTION', 'expected a camera object, got undefined', { field: 'camera' });
    const normalized = normalizeWavefrontCamera(camera);
    // Frames requested before the change render with the camera they were requested with.
    void this.afterSubmissions(() => {
      if (this.destroyed) return;
      this.config = { ...this.config, camera: normalized };
      this.writeFrameUniforms();
      this.resetAccumulation();
    }).catch(() => undefined);
  }

  async updateScene(update: WavefrontSceneUpdate): Promise<void> {
    // Frames requested before the update render the scene they were requested with.
    await this.submittedWork();
    const next = await prepareSceneUpdate(this.scene.normalized, this.sources, this.config, update, this.device.limits);
    this.assertUsable();
    // Every check passed: from here on nothing throws for the input.
    const p = next.prepared;
    let rebind = false;
    const ensure = (name: PlannedBufferName, bytes: number): GPUBuffer => {
      let buffer = this.resources[name];
      if (buffer.size < bytes) {
        buffer = this.buffers.replace(buffer, name, bytes, BufferUsage.STORAGE | BufferUsage.COPY_DST, 'scene');
        this.resources[name] = buffer;
        this.resourceMap[name] = buffer;
        rebind = true;
      }
      return buffer;
    };
    const write = (name: PlannedBufferName, data: ArrayBuffer | ArrayBufferView): void => {
      const bytes = ArrayBuffer.isView(data) ? data : new Uint8Array(data);
      this.device.queue.writeBuffer(ensure(name, bytes.byteLength), 0, bytes.buffer, bytes.byteOffset, bytes.byteLength);
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
    if (rebind) this.encoderOfWaves.rebind(createKernelBindGroups(this.device, this.kernels, this.resourceMap));
    this.device.queue.writeBuffer(this.resources.lighting, 0, next.lighting.uniforms);
    this.sources = { ...this.sources, lightingOptions: next.lightingOptions };
    this.scene = { instanceCount: next.scene.instances.length, sceneObjectCount: next.scene.sceneObjects.length, prepared: p, normalized: next.scene };
    this.lighting = next.lighting;
    this.config = { ...this.config, lighting: next.lightingConfig, ...(next.camera ? { camera: next.camera } : {}) };
    this.instanceIds = instanceIdTables(next.scene, p);
    // A new tree for the new primitives, in the renderer's build mode (the GPU builds it in 'gpu').
    this.acceleration?.destroy();
    this.acceleration = null;
    const r = this.resources;
    this.acceleration = await SceneAcceleration.create(this.device, p, { primitives: r.primitives, bvhNodes: r.bvhNodes, bvhParents: r.bvhParents }, this.buffers);
    this.writeFrameUniforms();
    this.resetAccumulation();
  }

  private resetAccumulation(): void {
    const encoder = this.device.createCommandEncoder();
    encoder.clearBuffer(this.resources.film);
    encoder.clearBuffer(this.resources.filmAovs);
    encoder.clearBuffer(this.resources.filmMoments);
    encoder.clearBuffer(this.resources.filmIds);
    this.device.queue.submit([encoder.finish()]);
    this.adaptive?.reset();
    this.samplesAccumulated = 0;
    this.pixelSamplesAccumulated = 0;
    this.denoisedFresh = false;
    this.frameCount = 0;
  }

  /** Waits until every frame requested so far has been submitted, so a read sees all of them. */
  private async submittedWork(): Promise<void> {
    this.assertUsable();
    await this.afterSubmissions(() => undefined);
    this.assertUsable();
  }

  async readRadiance(): Promise<WavefrontRadianceImage> {
    await this.submittedWork();
    return readMeanRadiance(this.device, this.resources.film, this.config.width, this.config.height);
  }

  async readDenoised(): Promise<WavefrontRadianceImage> {
    this.assertUsable();
    if (!this.denoiser) throw new GpuRendererError('INVALID_STATE', 'the denoiser is off: create the renderer with denoise: true', { field: 'denoise' });
    await this.submittedWork();
    const encoder = this.device.createCommandEncoder({ label: 'denoise' });
    if (this.encodeDenoise(encoder, null)) this.device.queue.submit([encoder.finish()]);
    return readRgbaImage(this.device, this.resources.denoised, this.config.width, this.config.height);
  }

  async readAov(name: WavefrontAovName): Promise<WavefrontRadianceImage> {
    this.assertUsable();
    if (!isWavefrontAovName(name)) throw new GpuRendererError('INVALID_OPTION', `unknown AOV ${JSON.stringify(name)} (${wavefrontAovNames.join(', ')})`, { field: 'name' });
    if (name !== 'sampleCount' && !this.config.aovs) throw new GpuRendererError('INVALID_STATE', 'AOVs were not enabled: create the renderer with aovs: true', { field: 'aovs' });
    await this.submittedWork();
    const r = this.resources;
    const adaptive = this.adaptive ? { error: r.adaptiveError, pixels: r.adaptivePixels } : null;
    return readAovImage(this.device, { film: r.film, aovs: r.filmAovs, moments: r.filmMoments, ids: r.filmIds, adaptive }, name, this.config.width, this.config.height, this.instanceIds);
  }

  async readPixels(): Promise<WavefrontPixelImage> {
    await this.submittedWork();
    const { width, height } = this.config;
    const encoder = this.device.createCommandEncoder();
    if (this.display.source === 'denoised') this.encodeDenoise(encoder, null);
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
      integrator: this.config.integrator,
      wavePaths: this.capacity,
      maxWavePaths: this.maxWavePaths,
      framesInFlight: this.config.framesInFlight,
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
      adaptive: this.adaptive ? { activePixels: this.adaptive.counts.activePixels, meanSamplesPerPixel: this.pixelSamplesAccumulated / (this.config.width * this.config.height) } : null,
      gpuParallelism: (({ adapterLimits, workgroupSize, physicalCoreCount }) => ({ adapterLimits, workgroupSize, physicalCoreCount }))(
        new DispatchTally().report(this.device.limits, rendererWavefrontComputeWorkgroupSize),
      ),
      ...this.outputState(),
    };
  }

  destroy(): void {
    if (this.destroyed) return;
    this.destroyed = true;
    this.display.detach();
    this.readbacks.destroy();
    this.acceleration?.destroy();
    this.denoiser?.destroy();
    this.buffers.destroy();
    this.atlasTexture.destroy();
    this.environmentTexture.destroy();
    if (this.ownsDevice) this.device.destroy();
  }
}
