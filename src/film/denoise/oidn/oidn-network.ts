/**
 * Open Image Denoise's `RT` network as WebGPU compute on the caller's device and buffers: the
 * weights are uploaded once per network; an image denoiser binds an input (a plain linear RGBA
 * image or a renderer's film with its AOV sums) and an output buffer, and encodes autoexposure, then
 * per tile the input process, the 16 convolutions (conv.wesl) and the output process into the
 * caller's command encoder. Nothing goes through the CPU. Tiles overlap (OIDN's receptive field) and
 * share one set of tensor buffers, sized for a memory budget and the device's binding limits.
 */
import { GpuRendererError } from '../../../errors/gpu-renderer-error.ts';
import { oidnConvUniformsLayout, oidnImageUniformsLayout } from '../../../gpu-layout/records.ts';
import { writeStruct } from '../../../gpu-layout/struct-layout.ts';
import { BufferUsage } from '../../../gpu/webgpu-constants.ts';
import { allShaderFeatures } from '../../../shaders/features.ts';
import type { ProgramName } from '../../../shaders/programs.ts';
import { computePipeline, type KernelPipeline } from '../../../shaders/program-pipelines.ts';
import { oidnBindings, type OidnBindingName } from './bindings.ts';
import { encodeValues, packConv, planTensors, planTiles, type OidnPrecision, type PackedConv, type TilePlan, type TensorPlan } from './packing.ts';
import { autoexposureBinSize } from './transfer.ts';
import { unetReceptiveField, type UNetModel } from './unet.ts';

/** Where the network reads its input: buffers of vec4f per pixel (row-major, top row first). */
export interface OidnImageSource {
  /** Colour; with `divideByCount` the rgb sums of a film with the sample count in alpha. */
  color: GPUBuffer;
  /** vec4s per pixel of `color` (default 1). */
  colorStride?: number;
  /** Albedo rgb at vec4 `pixel * stride + offset` (models with 6 or 9 input channels). */
  albedo?: { buffer: GPUBuffer; stride?: number; offset?: number };
  /** Shading normal xyz, any length (models with 9 input channels). */
  normal?: { buffer: GPUBuffer; stride?: number; offset?: number };
  /**
   * Exact (noise-free) emission rgb taken out of the colour before the network and added back to
   * its output unchanged, e.g. emitters seen directly: the network then neither blurs nor brightens
   * their edges.
   */
  emission?: { buffer: GPUBuffer; stride?: number; offset?: number };
  /** The colour, albedo and normal are sums over the colour's alpha (a film): divide by it. */
  divideByCount?: boolean;
}

export interface OidnImageOptions {
  /** Scratch memory budget of the tensors, bytes; tiles shrink to fit. Default 1 GiB. */
  maxMemoryBytes?: number;
  /** Fixed input scale instead of autoexposure (OIDN's `inputScale`). */
  inputScale?: number;
}

/** Allocates the GPU buffers (default: the device's createBuffer). */
export type OidnBufferAllocator = (label: string, size: number, usage: number) => GPUBuffer;

export const defaultOidnMaxMemoryBytes = 1024 * 1024 * 1024;

const bindingOf = (name: string): number => oidnBindings[name as OidnBindingName].binding;

export interface OidnPipelines {
  readonly precision: OidnPrecision;
  /** @internal */
  readonly kernels: NetworkPipelines;
}

interface NetworkPipelines {
  conv: KernelPipeline;
  exposureBins: KernelPipeline;
  exposureReduce: KernelPipeline;
  input: KernelPipeline;
  output: KernelPipeline;
}

/** Compiles the network's programs for a precision (once per renderer; the slow part on software drivers). */
export async function compileOidnPipelines(device: GPUDevice, precision: OidnPrecision): Promise<OidnPipelines> {
  return { precision, kernels: await networkPipelines(device, precision) };
}

async function networkPipelines(device: GPUDevice, precision: OidnPrecision): Promise<NetworkPipelines> {
  const program = (name: 'oidnConv' | 'oidnInput' | 'oidnOutput'): ProgramName => (precision === 'f16' ? `${name}F16` : name);
  device.pushErrorScope('validation');
  let pipelines: NetworkPipelines | undefined;
  let failure: unknown;
  try {
    const [conv, exposureBins, exposureReduce, input, output] = await Promise.all([
      computePipeline(device, oidnBindings, program('oidnConv'), 'oidn_conv3x3', allShaderFeatures),
      computePipeline(device, oidnBindings, 'oidnExposure', 'oidn_exposure_bins', allShaderFeatures),
      computePipeline(device, oidnBindings, 'oidnExposure', 'oidn_exposure_reduce', allShaderFeatures),
      computePipeline(device, oidnBindings, program('oidnInput'), 'oidn_input', allShaderFeatures),
      computePipeline(device, oidnBindings, program('oidnOutput'), 'oidn_output', allShaderFeatures),
    ]);
    pipelines = { conv, exposureBins, exposureReduce, input, output };
  } catch (error) {
    failure = error;
  }
  const validation = await device.popErrorScope();
  if (failure !== undefined) throw failure;
  if (validation) throw new GpuRendererError('GPU_VALIDATION_FAILED', `OIDN pipeline creation failed: ${validation.message}`);
  return pipelines!;
}

function bindGroup(device: GPUDevice, kernel: KernelPipeline, resources: Partial<Record<OidnBindingName, GPUBuffer>>, label: string): GPUBindGroup {
  return device.createBindGroup({
    label,
    layout: kernel.groups[0]!,
    entries: kernel.bindingsByGroup[0]!.map((name) => {
      const buffer = resources[name as OidnBindingName];
      if (!buffer) throw new Error(`${label}: no buffer for ${name}`);
      return { binding: bindingOf(name), resource: { buffer } };
    }),
  });
}

/** The precision a device runs the network in: f16 where it has shader-f16, unless asked otherwise. */
export function oidnPrecisionFor(device: GPUDevice, requested: 'auto' | OidnPrecision = 'auto'): OidnPrecision {
  const f16 = device.features.has('shader-f16');
  if (requested === 'f16' && !f16) throw new GpuRendererError('INVALID_OPTION', "the device has no 'shader-f16' feature (request it when creating the device)", { field: 'denoise.precision' });
  return requested === 'auto' ? (f16 ? 'f16' : 'f32') : requested;
}

/** The network's weights on a device, and its pipelines. Create image denoisers from it. */
export class OidnNetwork {
  readonly device: GPUDevice;
  readonly model: UNetModel;
  readonly precision: OidnPrecision;
  private readonly pipelines: NetworkPipelines;
  private readonly convs: { packed: PackedConv; weights: GPUBuffer }[];
  private destroyed = false;

  /** Uploads the weights; `pipelines` from compileOidnPipelines on the same device. */
  constructor(device: GPUDevice, model: UNetModel, pipelines: OidnPipelines, createBuffer: OidnBufferAllocator = (label, size, usage) => device.createBuffer({ label, size, usage })) {
    this.device = device;
    this.model = model;
    this.precision = pipelines.precision;
    this.pipelines = pipelines.kernels;
    this.convs = model.convs.map((conv) => {
      const packed = packConv(conv);
      const bytes = encodeValues(packed.values, this.precision);
      const weights = createBuffer(`oidn ${conv.name} weights`, bytes.byteLength, BufferUsage.STORAGE | BufferUsage.COPY_DST);
      device.queue.writeBuffer(weights, 0, bytes);
      return { packed, weights };
    });
  }

  /** Compiles the pipelines and uploads the weights. */
  static async create(device: GPUDevice, model: UNetModel, options: { precision?: 'auto' | OidnPrecision; createBuffer?: OidnBufferAllocator } = {}): Promise<OidnNetwork> {
    const pipelines = await compileOidnPipelines(device, oidnPrecisionFor(device, options.precision));
    return new OidnNetwork(device, model, pipelines, options.createBuffer);
  }

  /** Bytes of the uploaded weights. */
  get weightBytes(): number {
    return this.convs.reduce((a, c) => a + c.weights.size, 0);
  }

  /**
   * A denoiser of `width` x `height` images from `source` into `output` (vec4f per pixel: rgb, 1).
   * It owns its tensors and per-tile constants; destroy it when done.
   */
  createImageDenoiser(width: number, height: number, source: OidnImageSource, output: GPUBuffer, options: OidnImageOptions = {}, createBuffer?: OidnBufferAllocator): OidnImageDenoiser {
    if (this.destroyed) throw new GpuRendererError('INVALID_STATE', 'the OIDN network has been destroyed');
    const channels = this.model.inputChannels;
    if (channels >= 6 && !source.albedo) throw new GpuRendererError('INVALID_OPTION', `the ${channels}-channel model needs an albedo input`, { field: 'albedo' });
    if (channels >= 9 && !source.normal) throw new GpuRendererError('INVALID_OPTION', `the ${channels}-channel model needs a normal input`, { field: 'normal' });
    return new OidnImageDenoiser(this.device, this, width, height, source, output, options, createBuffer);
  }

  /** @internal The pieces an image denoiser binds. */
  parts(): { pipelines: NetworkPipelines; convs: OidnNetwork['convs'] } {
    return { pipelines: this.pipelines, convs: this.convs };
  }

  destroy(): void {
    if (this.destroyed) return;
    this.destroyed = true;
    for (const c of this.convs) c.weights.destroy();
  }
}

/** One image size, source and output: tiles, tensors and bind groups, encoded on demand. */
export class OidnImageDenoiser {
  readonly width: number;
  readonly height: number;
  readonly tiles: TilePlan;
  readonly tensors: TensorPlan;
  private readonly device: GPUDevice;
  private readonly network: OidnNetwork;
  private readonly buffers: GPUBuffer[] = [];
  private readonly exposure: { bins: [number, number]; groups: GPUBindGroup[] };
  private readonly convGroups: GPUBindGroup[];
  private readonly tileGroups: { input: GPUBindGroup; output: GPUBindGroup }[];

  constructor(device: GPUDevice, network: OidnNetwork, width: number, height: number, source: OidnImageSource, output: GPUBuffer, options: OidnImageOptions, createBuffer?: OidnBufferAllocator) {
    this.device = device;
    this.network = network;
    this.width = width;
    this.height = height;
    const { pipelines, convs } = network.parts();
    const model = network.model;
    const precision = network.precision;
    const budget = options.maxMemoryBytes ?? defaultOidnMaxMemoryBytes;
    const limit = Math.min(device.limits.maxStorageBufferBindingSize, device.limits.maxBufferSize);
    const fits = (w: number, h: number): boolean => {
      const plan = planTensors(model, w, h, precision);
      return plan.totalBytes <= budget && Math.max(...plan.slotBytes) <= limit;
    };
    this.tiles = planTiles(width, height, Math.ceil(unetReceptiveField[model.variant] / 2 / 16) * 16, fits);
    const tw = this.tiles.tileWidth, th = this.tiles.tileHeight;
    this.tensors = planTensors(model, tw, th, precision);
    if (Math.max(...this.tensors.slotBytes) > limit) {
      throw new GpuRendererError('INVALID_OPTION', `the smallest OIDN tile needs a ${Math.max(...this.tensors.slotBytes)}-byte buffer; the device binds ${limit}`, { field: 'denoise.maxMemoryMB' });
    }
    const allocate = createBuffer ?? ((label: string, size: number, usage: number) => device.createBuffer({ label, size, usage }));
    const create = (label: string, size: number, usage: number): GPUBuffer => {
      const b = allocate(label, Math.max(16, Math.ceil(size / 16) * 16), usage);
      this.buffers.push(b);
      return b;
    };
    const slots = this.tensors.slotBytes.map((bytes, i) => create(`oidn tensor ${i}`, bytes, BufferUsage.STORAGE));
    const slotOf = (name: string): GPUBuffer => slots[this.tensors.tensors.get(name)!.slot]!;
    const dummy = create('oidn unused source', 16, BufferUsage.STORAGE);
    const scale = create('oidn input scale', 16, BufferUsage.STORAGE);
    const bins: [number, number] = [Math.ceil(width / autoexposureBinSize), Math.ceil(height / autoexposureBinSize)];
    const exposureBins = create('oidn exposure bins', bins[0] * bins[1] * 4, BufferUsage.STORAGE);

    // Convolution constants (the same for every tile) and bind groups.
    this.convGroups = model.convs.map((conv, i) => {
      const c = convs[i]!;
      const data = new ArrayBuffer(oidnConvUniformsLayout.size);
      writeStruct(oidnConvUniformsLayout, new DataView(data), 0, {
        size: [tw >> conv.level, th >> conv.level],
        sourceA: c.packed.sourceGroups[0],
        sourceB: c.packed.sourceGroups[1],
        upsample: conv.upsample ? 1 : 0,
        pool: conv.pool ? 1 : 0,
        destination: c.packed.destinationGroups,
        blocks: c.packed.blocks,
      });
      const uniforms = create(`oidn ${conv.name}`, data.byteLength, BufferUsage.UNIFORM | BufferUsage.COPY_DST);
      device.queue.writeBuffer(uniforms, 0, data);
      return bindGroup(device, pipelines.conv, {
        oidnConv: uniforms,
        oidnSourceA: slotOf(conv.sources[0]),
        oidnSourceB: conv.sources[1] ? slotOf(conv.sources[1]) : dummy,
        oidnWeights: c.weights,
        oidnDestination: slotOf(conv.name),
      }, `oidn ${conv.name}`);
    });

    // Per-tile constants of the image passes.
    const sourceResources = {
      oidnColor: source.color,
      oidnAlbedo: source.albedo?.buffer ?? source.color,
      oidnNormal: source.normal?.buffer ?? source.color,
      oidnEmission: source.emission?.buffer ?? source.color,
    };
    const imageUniforms = (tile: TilePlan['tiles'][number] | null): GPUBuffer => {
      const data = new ArrayBuffer(oidnImageUniformsLayout.size);
      writeStruct(oidnImageUniformsLayout, new DataView(data), 0, {
        imageSize: [width, height],
        tileOrigin: tile?.origin ?? [0, 0],
        tileSize: [tw, th],
        writeMin: tile?.writeMin ?? [0, 0],
        writeMax: tile?.writeMax ?? [0, 0],
        exposureBins: bins,
        colorStride: source.colorStride ?? 1,
        divideByCount: source.divideByCount ? 1 : 0,
        albedoStride: source.albedo?.stride ?? 1,
        albedoOffset: source.albedo?.offset ?? 0,
        normalStride: source.normal?.stride ?? 1,
        normalOffset: source.normal?.offset ?? 0,
        emissionStride: source.emission ? (source.emission.stride ?? 1) : 0,
        emissionOffset: source.emission?.offset ?? 0,
        inputChannels: model.inputChannels,
        autoexposure: options.inputScale === undefined ? 1 : 0,
        inputScale: options.inputScale ?? 1,
      });
      const buffer = create('oidn image constants', data.byteLength, BufferUsage.UNIFORM | BufferUsage.COPY_DST);
      device.queue.writeBuffer(buffer, 0, data);
      return buffer;
    };
    const whole = imageUniforms(null);
    this.exposure = {
      bins,
      groups: [pipelines.exposureBins, pipelines.exposureReduce].map((k, i) =>
        bindGroup(device, k, { oidnImage: whole, oidnScale: scale, oidnExposureBins: exposureBins, ...sourceResources }, `oidn exposure ${i}`),
      ),
    };
    const last = model.convs[model.convs.length - 1]!.name;
    this.tileGroups = this.tiles.tiles.map((tile, i) => {
      const uniforms = imageUniforms(tile);
      return {
        input: bindGroup(device, pipelines.input, { oidnImage: uniforms, oidnScale: scale, oidnDestination: slotOf('input'), ...sourceResources }, `oidn input ${i}`),
        output: bindGroup(device, pipelines.output, { oidnImage: uniforms, oidnScale: scale, oidnSourceA: slotOf(last), oidnOutput: output, ...sourceResources }, `oidn output ${i}`),
      };
    });
  }

  /** Bytes of the tensors and constants this denoiser allocated. */
  get memoryBytes(): number {
    return this.buffers.reduce((a, b) => a + b.size, 0);
  }

  /** Dispatches the denoiser encodes (for dispatch tallies): [workgroups, invocations per workgroup]. */
  dispatches(): [number, number][] {
    const out: [number, number][] = [[this.exposure.bins[0] * this.exposure.bins[1], 256], [1, 256]];
    const tw = this.tiles.tileWidth, th = this.tiles.tileHeight;
    const { convs } = this.network.parts();
    for (const tile of this.tiles.tiles) {
      out.push([Math.ceil(tw / 8) * Math.ceil(th / 8), 64]);
      this.network.model.convs.forEach((conv, i) => out.push([Math.ceil((tw >> conv.level) / 16) * Math.ceil((th >> conv.level) / 16) * convs[i]!.packed.blocks, 64]));
      out.push([Math.ceil((tile.writeMax[0] - tile.writeMin[0]) / 8) * Math.ceil((tile.writeMax[1] - tile.writeMin[1]) / 8), 64]);
    }
    return out;
  }

  /** Encodes the whole denoise (one compute pass, optionally timed) into `encoder`. */
  encode(encoder: GPUCommandEncoder, timestampWrites?: GPUComputePassTimestampWrites): void {
    const { pipelines, convs } = this.network.parts();
    const model = this.network.model;
    const tw = this.tiles.tileWidth, th = this.tiles.tileHeight;
    const pass = encoder.beginComputePass({ label: 'oidn', ...(timestampWrites ? { timestampWrites } : {}) });
    pass.setPipeline(pipelines.exposureBins.pipeline);
    pass.setBindGroup(0, this.exposure.groups[0]!);
    pass.dispatchWorkgroups(this.exposure.bins[0], this.exposure.bins[1]);
    pass.setPipeline(pipelines.exposureReduce.pipeline);
    pass.setBindGroup(0, this.exposure.groups[1]!);
    pass.dispatchWorkgroups(1);
    this.tiles.tiles.forEach((tile, t) => {
      const groups = this.tileGroups[t]!;
      pass.setPipeline(pipelines.input.pipeline);
      pass.setBindGroup(0, groups.input);
      pass.dispatchWorkgroups(Math.ceil(tw / 8), Math.ceil(th / 8));
      pass.setPipeline(pipelines.conv.pipeline);
      model.convs.forEach((conv, i) => {
        pass.setBindGroup(0, this.convGroups[i]!);
        pass.dispatchWorkgroups(Math.ceil((tw >> conv.level) / 16), Math.ceil((th >> conv.level) / 16), convs[i]!.packed.blocks);
      });
      pass.setPipeline(pipelines.output.pipeline);
      pass.setBindGroup(0, groups.output);
      pass.dispatchWorkgroups(Math.ceil((tile.writeMax[0] - tile.writeMin[0]) / 8), Math.ceil((tile.writeMax[1] - tile.writeMin[1]) / 8));
    });
    pass.end();
  }

  destroy(): void {
    for (const b of this.buffers) b.destroy();
    this.buffers.length = 0;
  }
}
