import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { requireInteger } from '../errors/validate.ts';
import { acquireGpuDevice } from '../gpu/acquire-device.ts';
import { BufferUsage } from '../gpu/webgpu-constants.ts';
import {
  bounceUniformsLayout,
  dynamicUniformStride,
  frameUniformsLayout,
  queueCounterCount,
  queueCounterSlots,
  rendererWavefrontComputeWorkgroupSize,
  resolveUniformsLayout,
  waveUniformsLayout,
} from '../gpu-layout/records.ts';
import { writeStruct } from '../gpu-layout/struct-layout.ts';
import type { WavefrontCameraInput } from '../scene/types.ts';
import { normalizeWavefrontCamera } from './camera.ts';
import { resolveCanvasTarget, preferredCanvasFormat } from './canvas-target.ts';
import { createWavefrontPathTracingComputeConfig, type WavefrontPathTracingComputeConfig } from './config.ts';
import { GpuBufferSet, readGpuBuffer } from './gpu-buffers.ts';
import { wavefrontBindingSlots, wavefrontKernels, type WavefrontBindingName, type WavefrontKernelName } from './kernels.ts';
import { createPresentPipeline, createWavefrontPipelines, type WavefrontPipelines } from './pipelines.ts';
import { checkWavefrontDeviceLimits, prepareWavefrontScene, validateWavefrontScene, wavefrontBufferPlan, type PreparedWavefrontScene } from './scene-preparation.ts';
import { createWavefrontPathTracingComputeShaderSource } from './shader-source.ts';
import { composeShader } from '../shaders/modules.ts';
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

/** Most waves (tile x sample) encoded into one command buffer, bounding submission size. */
const maxWavesPerSubmission = 16;
const toneMappingIds = { neutral: 0, aces: 1, linear: 2 } as const;

const pipelineCache = new WeakMap<GPUDevice, Promise<WavefrontPipelines>>();

function pipelinesFor(device: GPUDevice): Promise<WavefrontPipelines> {
  let p = pipelineCache.get(device);
  if (!p) {
    p = createWavefrontPipelines(device, createWavefrontPathTracingComputeShaderSource());
    pipelineCache.set(device, p);
    p.catch(() => pipelineCache.delete(device));
  }
  return p;
}

interface Wave {
  tileOrigin: [number, number];
  tileSize: [number, number];
  sampleIndex: number;
}

interface KernelBinding {
  pipeline: GPUComputePipeline;
  groups: GPUBindGroup[];
  /** Which dynamic uniforms group 2 carries, in binding order. */
  dynamic: ('wave' | 'bounce')[];
}

/**
 * Creates the wavefront path tracer: validates every option and the scene (typed errors naming the
 * field; nothing is allocated for invalid input), acquires or shares a device, builds the BVH on the
 * CPU in event-loop-friendly slices, uploads the scene once and compiles the kernels.
 */
export async function createWavefrontPathTracingComputeRenderer(options: WavefrontPathTracingOptions): Promise<WavefrontPathTracingRenderer> {
  const config = createWavefrontPathTracingComputeConfig(options);
  const scene = validateWavefrontScene(options.meshes, options.sceneObjects);
  const canvas = options.canvas !== undefined ? resolveCanvasTarget(options.canvas) : null;
  const acquired = await acquireGpuDevice({
    ...(options.device ? { device: options.device } : {}),
    ...(options.powerPreference ? { powerPreference: options.powerPreference } : {}),
  });
  try {
    const plan = wavefrontBufferPlan(scene.triangleCount, scene.sceneObjects.length, config);
    checkWavefrontDeviceLimits(acquired.device.limits, plan);
    const prepared = await prepareWavefrontScene(scene, config.environment);
    const pipelines = await pipelinesFor(acquired.device);
    const renderer = new WavefrontRenderer(acquired.device, acquired.ownsDevice, acquired.adapterDescription, acquired.timestampQueries, config, prepared, pipelines, plan.capacity);
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
  private readonly timestamps: boolean;
  private config: WavefrontPathTracingComputeConfig;
  private readonly scene: PreparedWavefrontScene;
  private readonly pipelines: WavefrontPipelines;
  private readonly capacity: number;
  private readonly buffers: GpuBufferSet;
  private readonly resources: Record<WavefrontBindingName, GPUBuffer>;
  private readonly bindings: Record<WavefrontKernelName, KernelBinding>;
  private readonly countersBuffer: GPUBuffer;
  private readonly accumulationBuffer: GPUBuffer;
  private readonly resolveUniforms: GPUBuffer;
  private readonly resolvedPixels: GPUBuffer;
  private readonly resolveBindGroup: GPUBindGroup;
  private readonly querySet: GPUQuerySet | null;
  private readonly queryBuffer: GPUBuffer | null;
  private canvasContext: GPUCanvasContext | null = null;
  private present: { pipeline: GPURenderPipeline; bindGroup: GPUBindGroup } | null = null;
  private frameCount = 0;
  private samplesAccumulated = 0;
  private destroyed = false;
  private deviceLost = false;
  private deviceLostMessage = '';

  constructor(
    device: GPUDevice,
    ownsDevice: boolean,
    adapter: string,
    timestamps: boolean,
    config: WavefrontPathTracingComputeConfig,
    scene: PreparedWavefrontScene,
    pipelines: WavefrontPipelines,
    capacity: number,
  ) {
    this.device = device;
    this.ownsDevice = ownsDevice;
    this.adapter = adapter;
    this.timestamps = timestamps;
    this.config = config;
    this.scene = scene;
    this.pipelines = pipelines;
    this.capacity = capacity;
    const b = (this.buffers = new GpuBufferSet(device));
    const S = BufferUsage.STORAGE;
    const mesh = scene.mesh;
    this.resources = {
      frame: b.create('frame', frameUniformsLayout.size, BufferUsage.UNIFORM | BufferUsage.COPY_DST, 'scene'),
      triangles: b.upload('triangles', mesh.triangles, S, 'scene'),
      triangleAttributes: b.upload('triangleAttributes', mesh.attributes, S, 'scene'),
      bvhNodes: b.upload('bvhNodes', mesh.nodes, S, 'scene'),
      materials: b.upload('materials', scene.materials, S, 'scene'),
      sceneObjects: b.upload('sceneObjects', scene.sceneObjects, S, 'scene'),
      lights: b.upload('lights', mesh.lights.entries, S, 'scene'),
      paths: b.create('paths', 2 * capacity * 80, S, 'queue'),
      shadowRays: b.create('shadowRays', capacity * 48, S, 'queue'),
      counters: b.create('counters', queueCounterCount * 4, S | BufferUsage.COPY_SRC | BufferUsage.COPY_DST, 'queue'),
      tileRadiance: b.create('tileRadiance', capacity * 16, S, 'queue'),
      dispatchArgs: b.create('dispatchArgs', 32, S | BufferUsage.INDIRECT, 'queue'),
      accumulation: b.create('accumulation', config.width * config.height * 16, S | BufferUsage.COPY_SRC | BufferUsage.COPY_DST, 'frame'),
      wave: b.create('waveUniforms', maxWavesPerSubmission * dynamicUniformStride, BufferUsage.UNIFORM | BufferUsage.COPY_DST, 'queue'),
      bounce: b.create('bounceUniforms', 33 * dynamicUniformStride, BufferUsage.UNIFORM | BufferUsage.COPY_DST, 'queue'),
    };
    this.countersBuffer = this.resources.counters;
    this.accumulationBuffer = this.resources.accumulation;
    this.resolveUniforms = b.create('resolveUniforms', resolveUniformsLayout.size, BufferUsage.UNIFORM | BufferUsage.COPY_DST, 'frame');
    this.resolvedPixels = b.create('resolvedPixels', config.width * config.height * 4, S | BufferUsage.COPY_SRC, 'frame');
    this.resolveBindGroup = device.createBindGroup({
      layout: pipelines.resolveLayout,
      entries: [
        { binding: 0, resource: { buffer: this.resolveUniforms } },
        { binding: 1, resource: { buffer: this.accumulationBuffer } },
        { binding: 2, resource: { buffer: this.resolvedPixels } },
      ],
    });
    this.bindings = this.createKernelBindings();
    this.writeBounceUniforms();
    this.writeFrameUniforms();
    this.writeResolveUniforms();
    if (timestamps) {
      this.querySet = device.createQuerySet({ type: 'timestamp', count: 2 });
      this.queryBuffer = b.create('timestamps', 16, BufferUsage.QUERY_RESOLVE | BufferUsage.COPY_SRC, 'frame');
    } else {
      this.querySet = null;
      this.queryBuffer = null;
    }
    void device.lost.then((info) => {
      if (this.destroyed) return;
      this.deviceLost = true;
      this.deviceLostMessage = info.message || String(info.reason);
    });
  }

  private createKernelBindings(): Record<WavefrontKernelName, KernelBinding> {
    const out = {} as Record<WavefrontKernelName, KernelBinding>;
    for (const name of Object.keys(wavefrontKernels) as WavefrontKernelName[]) {
      const spec = wavefrontKernels[name];
      const kp = this.pipelines.kernels[name];
      const groups = kp.groupLayouts.map((layout, g) =>
        this.device.createBindGroup({
          layout,
          entries: (spec.bindings as readonly WavefrontBindingName[])
            .filter((n) => wavefrontBindingSlots[n].group === g)
            .map((n) => ({
              binding: wavefrontBindingSlots[n].binding,
              resource:
                n === 'wave'
                  ? { buffer: this.resources.wave, size: waveUniformsLayout.size }
                  : n === 'bounce'
                    ? { buffer: this.resources.bounce, size: bounceUniformsLayout.size }
                    : { buffer: this.resources[n] },
            })),
        }),
      );
      const dynamic = (spec.bindings as readonly WavefrontBindingName[])
        .filter((n): n is 'wave' | 'bounce' => n === 'wave' || n === 'bounce')
        .sort((a, b) => wavefrontBindingSlots[a].binding - wavefrontBindingSlots[b].binding);
      out[name] = { pipeline: kp.pipeline, groups, dynamic };
    }
    return out;
  }

  private writeBounceUniforms(): void {
    const data = new ArrayBuffer(33 * dynamicUniformStride);
    for (let d = 0; d <= 32; d++) {
      const even = d % 2 === 0;
      const slotView = new DataView(data, d * dynamicUniformStride, bounceUniformsLayout.size);
      writeStruct(bounceUniformsLayout, slotView, 0, {
        depth: d,
        inCounter: even ? queueCounterSlots.pathCount0 : queueCounterSlots.pathCount1,
        outCounter: even ? queueCounterSlots.pathCount1 : queueCounterSlots.pathCount0,
        inBase: even ? 0 : this.capacity,
        outBase: even ? this.capacity : 0,
      });
    }
    this.device.queue.writeBuffer(this.resources.bounce, 0, data);
  }

  private writeFrameUniforms(): void {
    const c = this.config;
    const s = this.scene;
    const data = new ArrayBuffer(frameUniformsLayout.size);
    writeStruct(frameUniformsLayout, new DataView(data), 0, {
      cameraPosition: c.camera.position,
      tanHalfFovY: c.camera.tanHalfFovY,
      cameraRight: c.camera.right,
      aspect: c.width / c.height,
      cameraUp: c.camera.trueUp,
      lightCount: s.mesh.lights.count,
      cameraForward: c.camera.forward,
      sceneObjectCount: s.sceneObjectCount,
      environmentRadiance: c.environment,
      environmentSelectProbability: s.environmentSelectProbability,
      sceneCenter: s.sceneCenter,
      sceneRadius: s.sceneRadius,
      imageSize: [c.width, c.height],
      maxDepth: c.maxDepth,
      seed: c.seed,
      queueCapacity: this.capacity,
      triangleCount: s.mesh.triangleCount,
      rayEpsilon: 1e-4 * s.sceneRadius,
    });
    this.device.queue.writeBuffer(this.resources.frame, 0, data);
  }

  private writeResolveUniforms(): void {
    const data = new ArrayBuffer(resolveUniformsLayout.size);
    writeStruct(resolveUniformsLayout, new DataView(data), 0, {
      imageSize: [this.config.width, this.config.height],
      toneMapping: toneMappingIds[this.config.toneMapping],
      exposure: this.config.exposure,
    });
    this.device.queue.writeBuffer(this.resolveUniforms, 0, data);
  }

  async attachCanvas(canvas: { width: number; height: number; getContext(kind: 'webgpu'): GPUCanvasContext | null }): Promise<void> {
    const context = canvas.getContext('webgpu');
    if (!context) throw new GpuRendererError('INVALID_CANVAS', 'the canvas has no WebGPU context', { field: 'canvas' });
    canvas.width = this.config.width;
    canvas.height = this.config.height;
    const format = preferredCanvasFormat();
    context.configure({ device: this.device, format, alphaMode: 'opaque' });
    const { pipeline, layout } = await createPresentPipeline(this.device, composeShader(['kernel-present']), format);
    const bindGroup = this.device.createBindGroup({
      layout,
      entries: [
        { binding: 0, resource: { buffer: this.resolveUniforms } },
        { binding: 1, resource: { buffer: this.accumulationBuffer } },
      ],
    });
    this.canvasContext = context;
    this.present = { pipeline, bindGroup };
  }

  private assertUsable(): void {
    if (this.destroyed) throw new GpuRendererError('RENDERER_DESTROYED', 'the renderer has been destroyed');
    if (this.deviceLost) throw new GpuRendererError('DEVICE_LOST', `the GPU device was lost: ${this.deviceLostMessage}`);
  }

  private waves(samples: number): Wave[] {
    const { width, height, tileSize } = this.config;
    const out: Wave[] = [];
    for (let s = 0; s < samples; s++) {
      for (let y = 0; y < height; y += tileSize) {
        for (let x = 0; x < width; x += tileSize) {
          out.push({ tileOrigin: [x, y], tileSize: [Math.min(tileSize, width - x), Math.min(tileSize, height - y)], sampleIndex: this.samplesAccumulated + s });
        }
      }
    }
    return out;
  }

  private dispatch(pass: GPUComputePassEncoder, name: WavefrontKernelName, offsets: { wave?: number; bounce?: number }, workgroups: number | { indirect: number }): void {
    const k = this.bindings[name];
    pass.setPipeline(k.pipeline);
    k.groups.forEach((group, g) => {
      if (g === 2) pass.setBindGroup(2, group, k.dynamic.map((d) => offsets[d] ?? 0));
      else pass.setBindGroup(g, group);
    });
    if (typeof workgroups === 'number') pass.dispatchWorkgroups(workgroups);
    else pass.dispatchWorkgroupsIndirect(this.resources.dispatchArgs, workgroups.indirect);
  }

  /** Encodes and submits the waves of `samples` samples per pixel; returns the last encoder's extras. */
  private submitFrame(samples: number, readStats: boolean): { stats: GPUBuffer | null; times: GPUBuffer | null } {
    const device = this.device;
    const waves = this.waves(samples);
    const maxDepth = this.config.maxDepth;
    device.queue.writeBuffer(this.countersBuffer, 0, new Uint32Array(queueCounterCount));
    let stats: GPUBuffer | null = null;
    let times: GPUBuffer | null = null;
    for (let first = 0; first < waves.length; first += maxWavesPerSubmission) {
      const batch = waves.slice(first, first + maxWavesPerSubmission);
      const isFirst = first === 0;
      const isLast = first + maxWavesPerSubmission >= waves.length;
      const uniforms = new ArrayBuffer(batch.length * dynamicUniformStride);
      batch.forEach((w, i) => writeStruct(waveUniformsLayout, new DataView(uniforms, i * dynamicUniformStride, waveUniformsLayout.size), 0, { ...w }));
      device.queue.writeBuffer(this.resources.wave, 0, uniforms);
      const encoder = device.createCommandEncoder({ label: 'wavefront frame' });
      const timestampWrites: GPUComputePassTimestampWrites | undefined =
        this.querySet && (isFirst || isLast)
          ? { querySet: this.querySet, ...(isFirst ? { beginningOfPassWriteIndex: 0 } : {}), ...(isLast ? { endOfPassWriteIndex: 1 } : {}) }
          : undefined;
      const pass = encoder.beginComputePass(timestampWrites ? { timestampWrites } : {});
      const wg = rendererWavefrontComputeWorkgroupSize;
      batch.forEach((w, i) => {
        const wave = i * dynamicUniformStride;
        const pixels = w.tileSize[0] * w.tileSize[1];
        this.dispatch(pass, 'camera', { wave }, Math.ceil(pixels / wg));
        for (let d = 0; d <= maxDepth; d++) {
          const bounce = d * dynamicUniformStride;
          this.dispatch(pass, 'prepareBounce', { bounce }, 1);
          this.dispatch(pass, 'extend', { bounce }, { indirect: 0 });
          this.dispatch(pass, 'shade', { wave, bounce }, { indirect: 0 });
          if (d < maxDepth) {
            this.dispatch(pass, 'prepareShadow', {}, 1);
            this.dispatch(pass, 'shadow', {}, { indirect: 16 });
          }
        }
        this.dispatch(pass, 'accumulate', { wave }, Math.ceil(pixels / wg));
      });
      pass.end();
      if (isLast) {
        if (readStats) {
          stats = device.createBuffer({ size: queueCounterCount * 4, usage: BufferUsage.MAP_READ | BufferUsage.COPY_DST });
          encoder.copyBufferToBuffer(this.countersBuffer, 0, stats, 0, queueCounterCount * 4);
          if (this.querySet && this.queryBuffer) {
            times = device.createBuffer({ size: 16, usage: BufferUsage.MAP_READ | BufferUsage.COPY_DST });
            encoder.resolveQuerySet(this.querySet, 0, 2, this.queryBuffer, 0);
            encoder.copyBufferToBuffer(this.queryBuffer, 0, times, 0, 16);
          }
        }
        this.encodePresent(encoder);
      }
      device.queue.submit([encoder.finish()]);
    }
    this.samplesAccumulated += samples;
    this.frameCount += 1;
    return { stats, times };
  }

  private encodePresent(encoder: GPUCommandEncoder): void {
    if (!this.canvasContext || !this.present) return;
    const pass = encoder.beginRenderPass({
      colorAttachments: [{ view: this.canvasContext.getCurrentTexture().createView(), loadOp: 'clear', storeOp: 'store', clearValue: { r: 0, g: 0, b: 0, a: 1 } }],
    });
    pass.setPipeline(this.present.pipeline);
    pass.setBindGroup(0, this.present.bindGroup);
    pass.draw(3);
    pass.end();
  }

  private samplesFor(options: WavefrontRenderFrameOptions | undefined): number {
    if (options?.samplesPerPixel === undefined) return this.config.samplesPerPixel;
    return requireInteger(options.samplesPerPixel, 'samplesPerPixel', { min: 1, max: 65536 });
  }

  async renderFrame(options?: WavefrontRenderFrameOptions): Promise<WavefrontFrameStats> {
    this.assertUsable();
    const samples = this.samplesFor(options);
    const started = performance.now();
    const waves = this.waves(samples).length;
    const { stats, times } = this.submitFrame(samples, true);
    let counters = new Uint32Array(queueCounterCount);
    let gpuTimeMs: number | null = null;
    try {
      if (stats) {
        await stats.mapAsync(0x0001);
        counters = new Uint32Array(stats.getMappedRange().slice(0));
      }
      if (times) {
        await times.mapAsync(0x0001);
        const t = new BigUint64Array(times.getMappedRange().slice(0));
        gpuTimeMs = t[1]! > t[0]! ? Number(t[1]! - t[0]!) / 1e6 : null;
      }
    } catch (error) {
      this.assertUsable();
      throw error;
    } finally {
      stats?.destroy();
      times?.destroy();
    }
    const slot = queueCounterSlots;
    const camera = counters[slot.cameraRays]!;
    const extension = counters[slot.extensionRays]!;
    const shadow = counters[slot.shadowRays]!;
    return {
      frame: this.frameCount,
      samplesAdded: samples,
      samplesAccumulated: this.samplesAccumulated,
      rays: { camera, extension, shadow, total: camera + extension + shadow },
      terminations: {
        russianRoulette: counters[slot.russianRouletteTerminations]!,
        maxDepth: counters[slot.maxDepthTerminations]!,
        escaped: counters[slot.escapedPaths]!,
      },
      invalidSamples: counters[slot.invalidSamples]!,
      gpuTimeMs,
      wallTimeMs: performance.now() - started,
      memory: this.memory(),
      tiles: waves / samples,
      waves,
    };
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
    encoder.clearBuffer(this.accumulationBuffer);
    this.device.queue.submit([encoder.finish()]);
    this.samplesAccumulated = 0;
    this.frameCount = 0;
  }

  async readRadiance(): Promise<WavefrontRadianceImage> {
    this.assertUsable();
    const { width, height } = this.config;
    const raw = new Float32Array(await readGpuBuffer(this.device, this.accumulationBuffer, width * height * 16));
    const data = new Float32Array(width * height * 4);
    for (let i = 0; i < width * height; i++) {
      const n = raw[4 * i + 3]!;
      const inv = n > 0 ? 1 / n : 0;
      data[4 * i] = raw[4 * i]! * inv;
      data[4 * i + 1] = raw[4 * i + 1]! * inv;
      data[4 * i + 2] = raw[4 * i + 2]! * inv;
      data[4 * i + 3] = 1;
    }
    return { width, height, data };
  }

  async readPixels(): Promise<WavefrontPixelImage> {
    this.assertUsable();
    const { width, height } = this.config;
    const encoder = this.device.createCommandEncoder();
    const pass = encoder.beginComputePass();
    pass.setPipeline(this.pipelines.resolve);
    pass.setBindGroup(0, this.resolveBindGroup);
    pass.dispatchWorkgroups(Math.ceil(width / 8), Math.ceil(height / 8));
    pass.end();
    this.device.queue.submit([encoder.finish()]);
    const bytes = await readGpuBuffer(this.device, this.resolvedPixels, width * height * 4);
    return { width, height, data: new Uint8ClampedArray(bytes) };
  }

  private memory(): WavefrontMemoryStats {
    const sceneBytes = this.buffers.bytes('scene');
    const queueBytes = this.buffers.bytes('queue');
    const frameBytes = this.buffers.bytes('frame');
    return { sceneBytes, queueBytes, frameBytes, totalBytes: sceneBytes + queueBytes + frameBytes };
  }

  getSnapshot(): WavefrontRendererSnapshot {
    return {
      width: this.config.width,
      height: this.config.height,
      frame: this.frameCount,
      samplesAccumulated: this.samplesAccumulated,
      maxDepth: this.config.maxDepth,
      samplesPerPixel: this.config.samplesPerPixel,
      tileSize: this.config.tileSize,
      triangleCount: this.scene.mesh.triangleCount,
      bvhNodeCount: this.scene.mesh.nodeCount,
      lightCount: this.scene.mesh.lights.count,
      sceneObjectCount: this.scene.sceneObjectCount,
      adapter: this.adapter,
      memory: this.memory(),
      destroyed: this.destroyed,
      deviceLost: this.deviceLost,
    };
  }

  destroy(): void {
    if (this.destroyed) return;
    this.destroyed = true;
    this.canvasContext?.unconfigure();
    this.querySet?.destroy();
    this.buffers.destroy();
    if (this.ownsDevice) this.device.destroy();
  }
}
