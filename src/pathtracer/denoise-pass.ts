import { pathTracerBindings } from '../gpu-layout/bindings.ts';
import { denoiseUniformsLayout } from '../gpu-layout/records.ts';
import { writeStruct } from '../gpu-layout/struct-layout.ts';
import { BufferUsage } from '../gpu/webgpu-constants.ts';
import type { ShaderFeatures } from '../shaders/features.ts';
import { createProgramBindGroups, type PathTracerResourceMap } from './bind-groups.ts';
import type { DispatchTally } from './dispatch-tally.ts';
import type { GpuBufferSet } from './gpu-buffers.ts';
import type { WavefrontDenoiseSettings } from './output-types.ts';
import { computePipeline, type KernelPipeline } from './pipelines.ts';

const bindingOf = (name: string): number => pathTracerBindings[name as keyof typeof pathTracerBindings].binding;

/**
 * A denoiser the renderer can run on a copy of its film: it encodes its passes and leaves
 * (rgb, 1) pixels in the `denoised` buffer. The a-trous filter below is the one shipped; a learned
 * denoiser would implement the same interface.
 */
export interface WavefrontDenoiser {
  readonly name: string;
  encode(encoder: GPUCommandEncoder, tally: DispatchTally | null): void;
}

export interface DenoisePipelines {
  prepare: KernelPipeline;
  atrous: KernelPipeline;
  finish: KernelPipeline;
}

export async function createDenoisePipelines(device: GPUDevice, features: ShaderFeatures): Promise<DenoisePipelines> {
  const [prepare, atrous, finish] = await Promise.all([
    computePipeline(device, 'denoiseInput', 'denoise_prepare', features),
    computePipeline(device, 'denoise', 'denoise_atrous', features),
    computePipeline(device, 'denoise', 'denoise_finish', features),
  ]);
  return { prepare, atrous, finish };
}

/** The uniform contents of every pass: the input pass, `iterations` a-trous passes, the finish. */
export function denoisePassUniforms(settings: WavefrontDenoiseSettings, width: number, height: number): Record<string, number | number[]>[] {
  const pixels = width * height;
  const common = { imageSize: [width, height], sigmaLuminance: settings.sigmaLuminance, sigmaNormal: settings.sigmaNormal, sigmaDepth: settings.sigmaDepth };
  const half = (i: number): number => (i % 2) * pixels;
  const passes: Record<string, number | number[]>[] = [{ ...common, stepSize: 0, inBase: 0, outBase: 0 }];
  for (let i = 0; i < settings.iterations; i++) passes.push({ ...common, stepSize: 1 << i, inBase: half(i), outBase: half(i + 1) });
  passes.push({ ...common, stepSize: 0, inBase: half(settings.iterations), outBase: 0 });
  return passes;
}

/**
 * The edge-avoiding a-trous denoiser on the renderer's film (src/post/denoise/atrous.wesl): the input
 * pass demodulates a copy of the mean radiance, `iterations` filter passes ping-pong between the two
 * halves of denoiseColor, the finish pass remodulates into `denoised`. Each pass has its own small
 * uniform buffer and bind groups, made once.
 */
export class AtrousDenoisePass implements WavefrontDenoiser {
  readonly name = 'svgf-atrous';
  private readonly passes: { pipeline: KernelPipeline; groups: GPUBindGroup[] }[] = [];
  private readonly width: number;
  private readonly height: number;

  constructor(device: GPUDevice, pipelines: DenoisePipelines, resources: PathTracerResourceMap, settings: WavefrontDenoiseSettings, width: number, height: number, buffers: GpuBufferSet) {
    this.width = width;
    this.height = height;
    const uniforms = denoisePassUniforms(settings, width, height);
    uniforms.forEach((values, i) => {
      const data = new ArrayBuffer(denoiseUniformsLayout.size);
      writeStruct(denoiseUniformsLayout, new DataView(data), 0, values);
      const buffer = i === 0 ? (resources.denoise as GPUBuffer) : buffers.create(`denoise pass ${i}`, data.byteLength, BufferUsage.UNIFORM | BufferUsage.COPY_DST, 'frame');
      device.queue.writeBuffer(buffer, 0, data);
      const pipeline = i === 0 ? pipelines.prepare : i === uniforms.length - 1 ? pipelines.finish : pipelines.atrous;
      this.passes.push({ pipeline, groups: createProgramBindGroups(device, pipeline, { ...resources, denoise: buffer }, bindingOf, `denoise pass ${i}`) });
    });
  }

  encode(encoder: GPUCommandEncoder, tally: DispatchTally | null): void {
    const x = Math.ceil(this.width / 8);
    const y = Math.ceil(this.height / 8);
    const pass = encoder.beginComputePass({ label: 'denoise' });
    for (const p of this.passes) {
      pass.setPipeline(p.pipeline.pipeline);
      p.groups.forEach((g, i) => pass.setBindGroup(i, g));
      pass.dispatchWorkgroups(x, y);
      tally?.direct(x * y, 64);
    }
    pass.end();
  }
}
