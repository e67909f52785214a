/**
 * The edge-avoiding à-trous denoiser (Dammertz et al., "Edge-Avoiding À-Trous Wavelet Transform for
 * fast Global Illumination Filtering", HPG 2010, with SVGF's variance-guided luminance weight): a
 * fast preview behind the WavefrontDenoiser interface of denoiser.ts.
 */
import { pathTracerBindings } from '../../gpu-layout/bindings.ts';
import { denoiseUniformsLayout } from '../../gpu-layout/records.ts';
import { writeStruct } from '../../gpu-layout/struct-layout.ts';
import { BufferUsage } from '../../gpu/webgpu-constants.ts';
import type { DenoiserDispatchTally, WavefrontDenoiser, WavefrontDenoiserEntry, WavefrontDenoiserTarget } from './denoiser.ts';
import type { WavefrontDenoiseSettings } from './settings.ts';
import type { ShaderFeatures } from '../../shaders/features.ts';
import { createProgramBindGroups, type PathTracerResourceMap } from '../../shaders/program-bind-groups.ts';
import { computePipeline, type KernelPipeline } from '../../shaders/program-pipelines.ts';

const bindingOf = (name: string): number => pathTracerBindings[name as keyof typeof pathTracerBindings].binding;

export interface DenoisePipelines {
  prepare: KernelPipeline;
  atrous: KernelPipeline;
  energyPartial: KernelPipeline;
  energyTotal: KernelPipeline;
  finish: KernelPipeline;
}

export async function createDenoisePipelines(device: GPUDevice, features: ShaderFeatures): Promise<DenoisePipelines> {
  const [prepare, atrous, energyPartial, energyTotal, finish] = await Promise.all([
    computePipeline(device, pathTracerBindings, 'denoiseInput', 'denoise_prepare', features),
    computePipeline(device, pathTracerBindings, 'denoise', 'denoise_atrous', features),
    computePipeline(device, pathTracerBindings, 'denoise', 'denoise_energy_partial', features),
    computePipeline(device, pathTracerBindings, 'denoise', 'denoise_energy_total', features),
    computePipeline(device, pathTracerBindings, 'denoise', 'denoise_finish', features),
  ]);
  return { prepare, atrous, energyPartial, energyTotal, finish };
}

type PassKind = keyof DenoisePipelines;

/**
 * The passes in order with their uniform contents: the input pass, `iterations` a-trous passes,
 * the two energy passes and the finish (the last three read the last a-trous output).
 */
export function denoisePassUniforms(settings: WavefrontDenoiseSettings, width: number, height: number): { kind: PassKind; uniforms: Record<string, number | number[]> }[] {
  const pixels = width * height;
  const common = { imageSize: [width, height], sigmaLuminance: settings.sigmaLuminance, sigmaNormal: settings.sigmaNormal, sigmaDepth: settings.sigmaDepth };
  const half = (i: number): number => (i % 2) * pixels;
  const passes: { kind: PassKind; uniforms: Record<string, number | number[]> }[] = [{ kind: 'prepare', uniforms: { ...common, stepSize: 0, inBase: 0, outBase: 0 } }];
  for (let i = 0; i < settings.iterations; i++) passes.push({ kind: 'atrous', uniforms: { ...common, stepSize: 1 << i, inBase: half(i), outBase: half(i + 1) } });
  const last = { ...common, stepSize: 0, inBase: half(settings.iterations), outBase: 0 };
  for (const kind of ['energyPartial', 'energyTotal', 'finish'] as const) passes.push({ kind, uniforms: last });
  return passes;
}

/**
 * The edge-avoiding a-trous denoiser on the renderer's film (src/film/denoise/atrous.wesl): the
 * input pass demodulates a copy of the mean radiance, `iterations` filter passes ping-pong between
 * the two halves of denoiseColor, two passes sum the raw and the filtered reflected radiance, the
 * finish pass remodulates into `denoised` with the whole image's energy restored. Each pass has its
 * own small uniform buffer and bind groups, made once.
 */
export class AtrousDenoisePass implements WavefrontDenoiser {
  readonly name = 'atrous';
  private readonly passes: { pipeline: KernelPipeline; groups: GPUBindGroup[]; single: boolean }[] = [];
  private readonly width: number;
  private readonly height: number;

  constructor(target: WavefrontDenoiserTarget, pipelines: DenoisePipelines, settings: WavefrontDenoiseSettings) {
    const { device, width, height } = target;
    const resources = target.resources as PathTracerResourceMap;
    this.width = width;
    this.height = height;
    denoisePassUniforms(settings, width, height).forEach(({ kind, uniforms }, i) => {
      const data = new ArrayBuffer(denoiseUniformsLayout.size);
      writeStruct(denoiseUniformsLayout, new DataView(data), 0, uniforms);
      const buffer = i === 0 ? (resources.denoise as GPUBuffer) : target.createBuffer(`denoise pass ${i}`, data.byteLength, BufferUsage.UNIFORM | BufferUsage.COPY_DST);
      device.queue.writeBuffer(buffer, 0, data);
      const pipeline = pipelines[kind];
      this.passes.push({ pipeline, groups: createProgramBindGroups(device, pipeline, { ...resources, denoise: buffer }, bindingOf, `denoise pass ${i}`), single: kind === 'energyTotal' });
    });
  }

  encode(encoder: GPUCommandEncoder, tally: DenoiserDispatchTally | null): void {
    const x = Math.ceil(this.width / 8);
    const y = Math.ceil(this.height / 8);
    const pass = encoder.beginComputePass({ label: 'denoise' });
    for (const p of this.passes) {
      pass.setPipeline(p.pipeline.pipeline);
      p.groups.forEach((g, i) => pass.setBindGroup(i, g));
      if (p.single) {
        pass.dispatchWorkgroups(1);
        tally?.direct(1, 256);
      } else {
        pass.dispatchWorkgroups(x, y);
        tally?.direct(x * y, 64);
      }
    }
    pass.end();
  }

  destroy(): void {
    // Everything it holds came from the target's createBuffer.
  }
}

/** The à-trous entry of the denoiser registry: runs on every WebGPU device. */
export const atrousDenoiser: WavefrontDenoiserEntry = {
  name: 'atrous',
  optionNames: ['iterations', 'sigmaLuminance', 'sigmaNormal', 'sigmaDepth'],
  // The guides and the noise estimate (FilmAovPixel.reflectedLuminanceSquared) are AOVs.
  reads: { aovs: true, moments: false },
  runsOn: () => true,
  async prepare(device, settings, _customWeights, features) {
    const pipelines = await createDenoisePipelines(device, features);
    return { name: 'atrous', create: (target) => new AtrousDenoisePass(target, pipelines, settings) };
  },
};
