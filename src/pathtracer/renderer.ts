import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { acquireGpuDevice } from '../gpu/acquire-device.ts';
import { rendererWavefrontComputeWorkgroupSize } from '../gpu-layout/constants.ts';
import { buildGpuLighting, type GpuLighting } from '../lighting/gpu-lighting.ts';
import type { WavefrontAovName } from '../film/aovs.ts';
import { normalizeWavefrontScene, type NormalizedScene } from '../scene/normalize-scene.ts';
import type { WavefrontCameraInput } from '../scene/types.ts';
import { allShaderFeatures } from '../shaders/features.ts';
import { createKernelBindGroups } from './bind-groups.ts';
import { checkBufferLimits, planBuffers, type PlannedBuffer, type PlannedBufferName } from './buffer-plan.ts';
import { resolveCanvasTarget } from '../film/display/canvas-target.ts';
import { createWavefrontPathTracingComputeConfig, type WavefrontPathTracingComputeConfig } from './config.ts';
import { AdaptiveScheduler, createAdaptivePipelines } from '../film/adaptive/scheduler.ts';
import type { WavefrontDenoiserFactory } from '../film/denoise/denoiser.ts';
import { prepareWavefrontDenoiser, resolveWavefrontDenoiser } from '../film/denoise/registry.ts';
import { DispatchTally } from './dispatch-tally.ts';
import { FrameReadbackRing } from './frame-stats.ts';
import { WavefrontEncoder } from './frame-encoder.ts';
import { GpuBufferSet } from './gpu-buffers.ts';
import { instanceIdTables } from './instance-ids.ts';
import { chooseIntegrator, pathTracerPipelines, type IntegratorChoice, type PathTracerPipelines } from './pipelines.ts';
import { FilmDisplay } from '../film/display/film-display.ts';
import { renderFrame, renderOnce, outputState } from './render-frame.ts';
import { readAov, readDenoised, readPixels, readRadiance } from './renderer-readback.ts';
import { rendererMemory, uploadRendererResources } from './renderer-resources.ts';
import { writeFrameUniforms, type RendererState } from './renderer-state.ts';
import { createAcceleration, updateCamera, updateGeometry, updateScene } from './renderer-updates.ts';
import { prepareGeometry, prepareMaterials, type PreparedScene } from './scene/prepare-scene.ts';
import type { WavefrontGeometryUpdate, WavefrontGeometryUpdateStats } from './scene/geometry-update.ts';
import { lightingOptionsOf, type SceneSources } from './scene-update.ts';
import { SubmissionQueue } from './submission-queue.ts';
import { planInput, sceneFeatures } from './scene-plan.ts';
import { instancingStats } from './scene/instancing.ts';
import { deviceWavePaths, gridWorkgroupLimit, waveBound } from './wave-capacity.ts';
import type {
  PathTracingIntegrator,
  WavefrontFrameStats,
  WavefrontPathTracingOptions,
  WavefrontPathTracingRenderer,
  WavefrontPixelImage,
  WavefrontRadianceImage,
  WavefrontRenderFrameOptions,
  WavefrontRendererSnapshot,
  WavefrontSceneUpdate,
} from './types.ts';
import { packBounceUniforms, packDisplayUniforms } from './uniforms.ts';

// The renderer's parts: scene upload (renderer-resources.ts), frame encoding (frame-passes.ts,
// render-frame.ts), readback (renderer-readback.ts) and updates (renderer-updates.ts), sharing one
// RendererState (renderer-state.ts). This file creates it and answers the public interface.

export { adaptiveStepSamples } from './frame-passes.ts';

/**
 * Creates the wavefront path tracer: validates every option and the scene (typed errors naming the
 * field; nothing is allocated for invalid input), acquires or shares a device, checks every buffer
 * against the device's limits, builds the BVH on the CPU in event-loop-friendly slices, uploads the
 * scene once and compiles the kernels specialised for the scene's features.
 */
export async function createWavefrontPathTracingComputeRenderer(options: WavefrontPathTracingOptions): Promise<WavefrontPathTracingRenderer> {
  const requested = createWavefrontPathTracingComputeConfig(options);
  const scene = normalizeWavefrontScene(options);
  const canvas = options.canvas !== undefined ? resolveCanvasTarget(options.canvas) : null;
  const specialization = options.shaderSpecialization ?? 'scene';
  if (specialization !== 'scene' && specialization !== 'off') throw new GpuRendererError('INVALID_OPTION', 'expected "scene" or "off"', { field: 'shaderSpecialization' });
  const acquired = await acquireGpuDevice({
    ...(options.device !== undefined ? { device: options.device } : {}),
    ...(options.powerPreference !== undefined ? { powerPreference: options.powerPreference } : {}),
  });
  try {
    resolveWavefrontDenoiser(requested.output, acquired.device);
    // A device too small for the megakernel runs the wavefront (the same image) and says so.
    const integrator = chooseIntegrator(requested.integrator, acquired.device.limits);
    const config: WavefrontPathTracingComputeConfig = { ...requested, integrator: integrator.integrator };
    const limits = acquired.device.limits;
    // Buffers are checked at the largest wave this renderer may grow to; they start at the work of
    // one call of samplesPerPixel and grow when a frame asks for more (growQueues).
    const maxWavePaths = waveBound(deviceWavePaths(limits), config.tileSize);
    const estimate = planInput(config, scene, maxWavePaths);
    checkBufferLimits(limits, planBuffers(estimate));
    const materials = prepareMaterials(scene, { maxTextureDimension2D: limits.maxTextureDimension2D, maxTextureArrayLayers: limits.maxTextureArrayLayers }, { energyCompensation: config.energyCompensation });
    const prepared = await prepareGeometry(scene, materials, { accelerationBuildMode: config.accelerationBuildMode, instancing: config.instancing });
    const lighting = buildGpuLighting({ config: config.lighting, triangles: { records: prepared.lights, count: prepared.lightCount }, sceneCenter: prepared.sceneCenter, sceneRadius: prepared.sceneRadius });
    const plan = planBuffers({ ...estimate, materialCells: prepared.materials.byteLength / 16, lightCount: prepared.lightCount, lightHeapCells: lighting.heap.byteLength / 16 });
    checkBufferLimits(limits, plan);
    const wavePaths = Math.min(maxWavePaths, config.width * config.height * config.samplesPerPixel);
    const initialPlan = planBuffers({ ...estimate, materialCells: prepared.materials.byteLength / 16, lightCount: prepared.lightCount, lightHeapCells: lighting.heap.byteLength / 16, wavePaths });
    const features = specialization === 'off' ? allShaderFeatures : sceneFeatures(prepared, lighting, config, acquired);
    const [pipelines, adaptivePipelines, denoisePipelines] = await Promise.all([
      pathTracerPipelines(acquired.device, features, config.integrator),
      config.output.adaptive ? createAdaptivePipelines(acquired.device, features) : null,
      config.output.denoise ? prepareWavefrontDenoiser(acquired.device, config.output.denoise, config.output.denoiseWeights, features) : null,
    ]);
    const sources: SceneSources = { materials, features, lightingOptions: lightingOptionsOf(options) };
    const renderer = new WavefrontRenderer(acquired, { requested: requested.integrator, ...integrator }, config, scene, sources, prepared, lighting, { ...pipelines, adaptive: adaptivePipelines, denoise: denoisePipelines }, initialPlan, { wavePaths, maxWavePaths });
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

type RendererPipelines = PathTracerPipelines & {
  adaptive: Awaited<ReturnType<typeof createAdaptivePipelines>> | null;
  denoise: WavefrontDenoiserFactory | null;
};

class WavefrontRenderer extends EventTarget implements WavefrontPathTracingRenderer {
  readonly device: GPUDevice;
  private readonly ownsDevice: boolean;
  private readonly adapter: string;
  private readonly atlasTexture: GPUTexture;
  private readonly environmentTexture: GPUTexture;
  private readonly s: RendererState;
  /** The integrator the options asked for, and the warning when another one runs. */
  private readonly integrator: IntegratorChoice & { requested: PathTracingIntegrator };

  constructor(
    acquired: { device: GPUDevice; ownsDevice: boolean; adapterDescription: string; timestampQueries: boolean; softwareAdapter: boolean },
    integrator: IntegratorChoice & { requested: PathTracingIntegrator },
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
    this.integrator = integrator;
    const b = new GpuBufferSet(device);
    const { resources, resourceMap: map, atlasTexture, environmentTexture, textureBytes } = uploadRendererResources(device, b, prepared, lighting, plan);
    this.atlasTexture = atlasTexture;
    this.environmentTexture = environmentTexture;
    const encoderOfWaves = new WavefrontEncoder(createKernelBindGroups(device, pipelines.kernels, map), {
      pixels: config.width * config.height,
      gridLimit: gridWorkgroupLimit(acquired.softwareAdapter, device.limits),
      integrator: config.integrator,
      shadingDispatch: resources.shadingDispatch,
    });
    const out = config.output;
    const display = new FilmDisplay(device, pipelines.resolve, map, out.denoise ? resources.denoised : undefined);
    if (out.denoise?.present === 'denoised') display.source = 'denoised';
    const adaptive = out.adaptive && pipelines.adaptive ? new AdaptiveScheduler(device, pipelines.adaptive, map, out.adaptive, config.width, config.height) : null;
    const denoiser = pipelines.denoise?.create({ device, width: config.width, height: config.height, resources: map, createBuffer: (label, size, usage) => b.create(label, size, usage, 'frame') }) ?? null;
    adaptive?.reset();
    const slots = config.framesInFlight;
    const readbacks = new FrameReadbackRing(device, slots, acquired.timestampQueries ? { querySet: device.createQuerySet({ type: 'timestamp', count: 2 * slots }), resolve: resources.timestamps } : null);
    const s: RendererState = (this.s = {
      device,
      events: this,
      config,
      scene: { instanceCount: scene.instances.length, sceneObjectCount: scene.sceneObjects.length, prepared, normalized: scene },
      sources,
      kernels: pipelines.kernels,
      acceleration: null,
      capacity: waves.wavePaths,
      maxWavePaths: waves.maxWavePaths,
      buffers: b,
      resources,
      resourceMap: map,
      lighting,
      textureBytes,
      encoderOfWaves,
      display,
      readbacks,
      submissions: new SubmissionQueue(),
      adaptive,
      denoiser,
      instanceIds: instanceIdTables(scene, prepared),
      frameCount: 0,
      samplesAccumulated: 0,
      pixelSamplesAccumulated: 0,
      denoisedFresh: false,
      destroyed: false,
      deviceLost: false,
      deviceLostMessage: '',
    });
    device.queue.writeBuffer(resources.bounce, 0, packBounceUniforms(config.maxDepth, s.capacity));
    writeFrameUniforms(s);
    this.writeDisplayUniforms();
    void device.lost.then((info) => {
      if (s.destroyed) return;
      s.deviceLost = true;
      s.deviceLostMessage = info.message || String(info.reason);
    });
  }

  /** Uploads or builds the BVH (accelerationBuildMode); called once by the factory. */
  createAcceleration(): Promise<void> {
    return createAcceleration(this.s);
  }

  updateGeometry(update: WavefrontGeometryUpdate): Promise<WavefrontGeometryUpdateStats> {
    return updateGeometry(this.s, update);
  }

  private writeDisplayUniforms(): void {
    const c = this.s.config;
    const exposure = c.exposure * 2 ** c.output.exposureEv;
    this.device.queue.writeBuffer(this.s.resources.displayUniforms, 0, packDisplayUniforms(c.width, c.height, c.toneMapping, exposure, c.output.presentationOutput));
    // The noise threshold applies to the image as displayed (Cycles multiplies by the film exposure).
    this.s.adaptive?.writeUniforms(c.width, c.height, exposure);
  }

  async attachCanvas(canvas: Parameters<FilmDisplay['attachCanvas']>[0]): Promise<void> {
    await this.s.display.attachCanvas(canvas, this.s.config.width, this.s.config.height);
  }

  renderFrame(options?: WavefrontRenderFrameOptions): Promise<WavefrontFrameStats> {
    return renderFrame(this.s, options);
  }

  renderOnce(options?: WavefrontRenderFrameOptions): void {
    renderOnce(this.s, options);
  }

  updateCamera(camera: WavefrontCameraInput): void {
    updateCamera(this.s, camera);
  }

  updateScene(update: WavefrontSceneUpdate): Promise<void> {
    return updateScene(this.s, update);
  }

  readRadiance(): Promise<WavefrontRadianceImage> {
    return readRadiance(this.s);
  }

  readDenoised(): Promise<WavefrontRadianceImage> {
    return readDenoised(this.s);
  }

  readAov(name: WavefrontAovName): Promise<WavefrontRadianceImage> {
    return readAov(this.s, name);
  }

  readPixels(): Promise<WavefrontPixelImage> {
    return readPixels(this.s);
  }

  getSnapshot(): WavefrontRendererSnapshot {
    const s = this.s;
    const p = s.scene.prepared;
    return {
      width: s.config.width,
      height: s.config.height,
      frame: s.frameCount,
      samplesAccumulated: s.samplesAccumulated,
      maxDepth: s.config.maxDepth,
      samplesPerPixel: s.config.samplesPerPixel,
      tileSize: s.config.tileSize,
      integrator: s.config.integrator,
      requestedIntegrator: this.integrator.requested,
      wavePaths: s.capacity,
      maxWavePaths: s.maxWavePaths,
      framesInFlight: s.config.framesInFlight,
      triangleCount: p.triangleCount,
      bvhNodeCount: p.bvh.nodeCount + (p.bottomLevels?.levels.reduce((sum, l) => sum + l.nodeCount, 0) ?? 0),
      bvhDepth: p.bvh.depth + (p.bottomLevels ? 1 + Math.max(...p.bottomLevels.levels.map((l) => l.depth)) : 0),
      instancing: instancingStats(s.scene.normalized, p.instancing),
      lightCount: s.lighting.boundedCount + s.lighting.directionalCount,
      sceneObjectCount: s.scene.sceneObjectCount,
      instanceCount: s.scene.instanceCount,
      textureCount: p.atlas.textureCount,
      warnings: this.integrator.warning === null ? p.warnings : [this.integrator.warning, ...p.warnings],
      adapter: this.adapter,
      memory: rendererMemory(s.buffers, s.textureBytes),
      destroyed: s.destroyed,
      deviceLost: s.deviceLost,
      adaptive: s.adaptive ? { activePixels: s.adaptive.counts.activePixels, meanSamplesPerPixel: s.pixelSamplesAccumulated / (s.config.width * s.config.height) } : null,
      gpuParallelism: (({ adapterLimits, workgroupSize, physicalCoreCount }) => ({ adapterLimits, workgroupSize, physicalCoreCount }))(
        new DispatchTally().report(this.device.limits, rendererWavefrontComputeWorkgroupSize),
      ),
      ...outputState(s),
    };
  }

  destroy(): void {
    const s = this.s;
    if (s.destroyed) return;
    s.destroyed = true;
    s.display.detach();
    s.readbacks.destroy();
    s.acceleration?.destroy();
    s.denoiser?.destroy();
    s.buffers.destroy();
    this.atlasTexture.destroy();
    this.environmentTexture.destroy();
    if (this.ownsDevice) this.device.destroy();
  }
}
