import { adaptiveListSlots } from '../../gpu-layout/constants.ts';
import { adaptiveUniformsLayout } from '../../gpu-layout/records.ts';
import { writeStruct } from '../../gpu-layout/struct-layout.ts';
import { BufferUsage, MapMode } from '../../gpu/webgpu-constants.ts';
import { createProgramBindGroups, type PathTracerResourceMap } from '../../shaders/program-bind-groups.ts';
import { pathTracerBindings } from '../../gpu-layout/bindings.ts';
import { computePipeline, type KernelPipeline } from '../../shaders/program-pipelines.ts';
import type { DispatchCounter } from '../dispatch-counter.ts';
import { maxSamplesPerFrame, type WavefrontAdaptiveSettings } from './settings.ts';
import type { ShaderFeatures } from '../../shaders/features.ts';
import { rendererWavefrontComputeWorkgroupSize } from '../../gpu-layout/constants.ts';

const bindingOf = (name: string): number => pathTracerBindings[name as keyof typeof pathTracerBindings].binding;

export interface AdaptivePipelines {
  error: KernelPipeline;
  compact: KernelPipeline;
}

export async function createAdaptivePipelines(device: GPUDevice, features: ShaderFeatures): Promise<AdaptivePipelines> {
  const [error, compact] = await Promise.all([
    computePipeline(device, pathTracerBindings, 'adaptiveSampling', 'adaptive_error', features),
    computePipeline(device, pathTracerBindings, 'adaptiveSampling', 'adaptive_compact', features),
  ]);
  return { error, compact };
}

/** Counts the last convergence test left on the GPU. */
export interface AdaptiveCounts {
  activePixels: number;
  estimatedRemainingPixelSamples: number;
}

/**
 * Adaptive sampling's GPU side and its CPU bookkeeping: the convergence test (per-pixel error, 3x3
 * dilation, compaction of the pixels still sampling into the list the next list waves draw from)
 * and the one readback per sampling step of the list length, which sizes the next step's waves.
 * Nothing is read back per wave; the waves bound themselves by the GPU's own count.
 */
export class AdaptiveScheduler {
  readonly settings: WavefrontAdaptiveSettings;
  private readonly device: GPUDevice;
  private readonly pixels: number;
  private readonly resources: PathTracerResourceMap;
  private readonly errorGroups: GPUBindGroup[];
  private readonly compactGroups: GPUBindGroup[];
  private readonly pipelines: AdaptivePipelines;
  /** The list length as last read back (all pixels after a reset). */
  counts: AdaptiveCounts;

  constructor(device: GPUDevice, pipelines: AdaptivePipelines, resources: PathTracerResourceMap, settings: WavefrontAdaptiveSettings, width: number, height: number) {
    this.device = device;
    this.pipelines = pipelines;
    this.resources = resources;
    this.settings = settings;
    this.pixels = width * height;
    this.errorGroups = createProgramBindGroups(device, pipelines.error, resources, bindingOf, 'adaptive_error');
    this.compactGroups = createProgramBindGroups(device, pipelines.compact, resources, bindingOf, 'adaptive_compact');
    this.counts = { activePixels: this.pixels, estimatedRemainingPixelSamples: this.pixels * settings.minimumSamplesPerPixel };
    this.writeUniforms(width, height, 1);
  }

  writeUniforms(width: number, height: number, exposure: number): void {
    const data = new ArrayBuffer(adaptiveUniformsLayout.size);
    writeStruct(adaptiveUniformsLayout, new DataView(data), 0, {
      imageSize: [width, height],
      threshold: this.settings.threshold,
      minimumSamples: this.settings.minimumSamplesPerPixel,
      exposure,
      sampleCeiling: maxSamplesPerFrame,
    });
    this.device.queue.writeBuffer(this.resources.adaptive as GPUBuffer, 0, data);
  }

  /** Every pixel active, in row-major order (a new accumulation). */
  reset(): void {
    const list = new Uint32Array(adaptiveListSlots.listStart + this.pixels);
    list[adaptiveListSlots.activeCount] = this.pixels;
    for (let p = 0; p < this.pixels; p++) list[adaptiveListSlots.listStart + p] = p;
    this.device.queue.writeBuffer(this.resources.adaptivePixels as GPUBuffer, 0, list);
    this.counts = { activePixels: this.pixels, estimatedRemainingPixelSamples: this.pixels * this.settings.minimumSamplesPerPixel };
  }

  /** Encodes the convergence test and a copy of the list header into a mappable buffer (returned). */
  encodeConvergence(encoder: GPUCommandEncoder, tally: DispatchCounter | null): GPUBuffer {
    const list = this.resources.adaptivePixels as GPUBuffer;
    encoder.clearBuffer(list, 0, adaptiveListSlots.listStart * 4);
    const workgroups = Math.ceil(this.pixels / rendererWavefrontComputeWorkgroupSize);
    const pass = encoder.beginComputePass({ label: 'adaptive sampling' });
    for (const [pipeline, groups] of [[this.pipelines.error, this.errorGroups], [this.pipelines.compact, this.compactGroups]] as const) {
      pass.setPipeline(pipeline.pipeline);
      groups.forEach((g, i) => pass.setBindGroup(i, g));
      pass.dispatchWorkgroups(workgroups);
      tally?.direct(workgroups, rendererWavefrontComputeWorkgroupSize);
    }
    pass.end();
    const staging = this.device.createBuffer({ label: 'adaptive counts', size: adaptiveListSlots.listStart * 4, usage: BufferUsage.MAP_READ | BufferUsage.COPY_DST });
    encoder.copyBufferToBuffer(list, 0, staging, 0, adaptiveListSlots.listStart * 4);
    return staging;
  }

  /** Maps the header copy and updates the counts. */
  async read(staging: GPUBuffer): Promise<AdaptiveCounts> {
    try {
      await staging.mapAsync(MapMode.READ);
      const words = new Uint32Array(staging.getMappedRange().slice(0));
      this.counts = {
        activePixels: words[adaptiveListSlots.activeCount]!,
        estimatedRemainingPixelSamples: words[adaptiveListSlots.predictedSamplesLo]! + words[adaptiveListSlots.predictedSamplesHi]! * 2 ** 32,
      };
      return this.counts;
    } finally {
      staging.destroy();
    }
  }
}
