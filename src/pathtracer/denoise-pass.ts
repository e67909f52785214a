/**
 * The renderer's denoisers behind the one interface of src/post/denoise/denoiser.ts: the
 * edge-avoiding a-trous filter (below) and Open Image Denoise's network on the film
 * (src/post/denoise/oidn), and prepareWavefrontDenoiser, which resolves the options against the
 * device, loads and compiles what the chosen one needs, and returns its factory.
 */
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { pathTracerBindings } from '../gpu-layout/bindings.ts';
import { denoiseUniformsLayout } from '../gpu-layout/records.ts';
import { writeStruct } from '../gpu-layout/struct-layout.ts';
import { BufferUsage } from '../gpu/webgpu-constants.ts';
import type { DenoiserDispatchTally, WavefrontDenoiser, WavefrontDenoiserFactory, WavefrontDenoiserTarget } from '../post/denoise/denoiser.ts';
import { compileOidnPipelines, OidnNetwork, oidnPrecisionFor, type OidnImageDenoiser, type OidnPipelines } from '../post/denoise/oidn/oidn-network.ts';
import type { UNetModel } from '../post/denoise/oidn/unet.ts';
import { loadOidnModel, oidnModelFromBytes, type OidnBuiltinWeights } from '../post/denoise/oidn/weights.ts';
import type { ShaderFeatures } from '../shaders/features.ts';
import { createProgramBindGroups, type PathTracerResourceMap } from './bind-groups.ts';
import type { WavefrontDenoiseSettings } from './output-types.ts';
import { computePipeline, type KernelPipeline } from '../shaders/program-pipelines.ts';

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
 * The edge-avoiding a-trous denoiser on the renderer's film (src/post/denoise/atrous.wesl): the
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

/** Open Image Denoise's network on the renderer's film (radiance and AOV sums over the sample count). */
export class OidnFilmDenoiser implements WavefrontDenoiser {
  readonly name = 'oidn';
  readonly network: OidnNetwork;
  readonly image: OidnImageDenoiser;

  constructor(target: WavefrontDenoiserTarget, model: UNetModel, pipelines: OidnPipelines, settings: WavefrontDenoiseSettings) {
    const film = target.resources.film as GPUBuffer;
    const aovs = target.resources.filmAovs as GPUBuffer;
    this.network = new OidnNetwork(target.device, model, pipelines, target.createBuffer);
    this.image = this.network.createImageDenoiser(
      target.width,
      target.height,
      {
        color: film,
        divideByCount: true,
        albedo: { buffer: aovs, stride: 3, offset: 0 },
        normal: { buffer: aovs, stride: 3, offset: 1 },
        ...(settings.emission === 'exact' ? { emission: { buffer: aovs, stride: 3, offset: 2 } } : {}),
      },
      target.resources.denoised as GPUBuffer,
      { maxMemoryBytes: settings.maxMemoryMB * 1024 * 1024 },
      target.createBuffer,
    );
  }

  encode(encoder: GPUCommandEncoder, tally: DenoiserDispatchTally | null): void {
    this.image.encode(encoder);
    if (tally) for (const [workgroups, size] of this.image.dispatches()) tally.direct(workgroups, size);
  }

  destroy(): void {
    this.image.destroy();
    this.network.destroy();
  }
}

/** Whether the device can run the OIDN network (the core WebGPU limits always can). */
export function oidnRunsOn(device: GPUDevice): boolean {
  const l = device.limits;
  return l.maxComputeWorkgroupStorageSize >= 8192 && l.maxStorageBuffersPerShaderStage >= 5 && l.maxComputeInvocationsPerWorkgroup >= 256;
}

/** Resolves `denoiser: 'auto'` in place: OIDN where the device runs it, else à-trous. */
export function resolveWavefrontDenoiser(output: { denoise: WavefrontDenoiseSettings | null }, device: GPUDevice): void {
  const requested = output.denoise;
  if (!requested) return;
  const runsOidn = oidnRunsOn(device);
  if (requested.denoiser === 'oidn' && !runsOidn) throw new GpuRendererError('INVALID_OPTION', "this device's limits are below what the OIDN network needs; use denoise: 'atrous'", { field: 'denoise.denoiser' });
  if (requested.denoiser === 'auto') output.denoise = { ...requested, denoiser: runsOidn ? 'oidn' : 'atrous' };
}

/**
 * Loads the OIDN weights and compiles the chosen denoiser's pipelines (after
 * resolveWavefrontDenoiser); returns its factory. Updates the settings to what runs: user weights
 * decide whether the network reads the albedo and normal AOVs (auxiliary), and precision 'auto'
 * becomes 'f16' or 'f32'.
 */
export async function prepareWavefrontDenoiser(
  device: GPUDevice,
  settings: WavefrontDenoiseSettings,
  customWeights: Uint8Array | null,
  features: ShaderFeatures,
): Promise<WavefrontDenoiserFactory> {
  if (settings.denoiser === 'auto') throw new Error('prepareWavefrontDenoiser: resolve the denoiser first');
  if (settings.denoiser === 'atrous') {
    const pipelines = await createDenoisePipelines(device, features);
    return { name: 'atrous', create: (target) => new AtrousDenoisePass(target, pipelines, settings) };
  }
  const model = customWeights ? oidnModelFromBytes(customWeights) : await loadOidnModel(settings.weights as OidnBuiltinWeights);
  settings.auxiliary = model.inputChannels > 3;
  settings.precision = oidnPrecisionFor(device, settings.precision);
  const pipelines = await compileOidnPipelines(device, settings.precision);
  return { name: 'oidn', create: (target) => new OidnFilmDenoiser(target, model, pipelines, settings) };
}
