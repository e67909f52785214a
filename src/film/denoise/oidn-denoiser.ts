/**
 * Open Image Denoise's U-Net (oidn/) on the renderer's film, behind the WavefrontDenoiser interface
 * of denoiser.ts: the network reads the film's radiance and AOV sums over the sample count.
 */
import { filmAovPixelLayout, filmPixelLayout } from '../../gpu-layout/records.ts';
import { fieldOf } from '../../gpu-layout/struct-layout.ts';
import type { DenoiserDispatchTally, WavefrontDenoiser, WavefrontDenoiserEntry, WavefrontDenoiserTarget } from './denoiser.ts';
import type { WavefrontDenoiseSettings } from './settings.ts';
import { compileOidnPipelines, OidnNetwork, oidnPrecisionFor, type OidnImageDenoiser, type OidnPipelines } from './oidn/oidn-network.ts';
import type { UNetModel } from './oidn/unet.ts';
import { loadOidnModel, oidnModelFromBytes, type OidnBuiltinWeights } from './oidn/weights.ts';

/** An AOV film field as the network's image source: vec4 `pixel * stride + offset`, its rgb. */
function aovSource(buffer: GPUBuffer, field: 'albedo' | 'normal' | 'emission'): { buffer: GPUBuffer; stride: number; offset: number } {
  return { buffer, stride: filmAovPixelLayout.size / 16, offset: fieldOf(filmAovPixelLayout, field).offset / 16 };
}

// The network reads the film as vec4s of (radiance sum, sample count) (divideByCount).
if (filmPixelLayout.size !== 16 || fieldOf(filmPixelLayout, 'radiance').offset !== 0 || fieldOf(filmPixelLayout, 'samples').offset !== 12) {
  throw new Error('FilmPixel is no longer (radiance sum, sample count) in one vec4: update the OIDN colour source');
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
        albedo: aovSource(aovs, 'albedo'),
        normal: aovSource(aovs, 'normal'),
        ...(settings.emission === 'exact' ? { emission: aovSource(aovs, 'emission') } : {}),
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

/**
 * The OIDN entry of the denoiser registry. Preparing loads the weights and compiles the pipelines,
 * and updates the settings to what runs: user weights decide whether the network reads the albedo
 * and normal AOVs (auxiliary), and precision 'auto' becomes 'f16' or 'f32'.
 */
export const oidnDenoiser: WavefrontDenoiserEntry = {
  name: 'oidn',
  optionNames: ['auxiliary', 'precision', 'emission', 'maxMemoryMB', 'weights'],
  reads: { aovs: true, moments: false },
  runsOn: oidnRunsOn,
  async prepare(device, settings, customWeights) {
    const model = customWeights ? oidnModelFromBytes(customWeights) : await loadOidnModel(settings.weights as OidnBuiltinWeights);
    settings.auxiliary = model.inputChannels > 3;
    settings.precision = oidnPrecisionFor(device, settings.precision);
    const pipelines = await compileOidnPipelines(device, settings.precision);
    return { name: 'oidn', create: (target) => new OidnFilmDenoiser(target, model, pipelines, settings) };
  },
};
