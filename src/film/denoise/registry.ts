/**
 * The denoisers the renderer runs, by name. The renderer only calls resolveWavefrontDenoiser and
 * prepareWavefrontDenoiser; a new denoiser implements WavefrontDenoiserEntry (denoiser.ts) and
 * takes a place in this table.
 */
import { GpuRendererError } from '../../errors/gpu-renderer-error.ts';
import type { ShaderFeatures } from '../../shaders/features.ts';
import { atrousDenoiser } from './atrous-denoiser.ts';
import type { WavefrontDenoiserEntry, WavefrontDenoiserFactory, WavefrontDenoiserName } from './denoiser.ts';
import { oidnDenoiser } from './oidn-denoiser.ts';
import type { WavefrontDenoiseSettings } from './settings.ts';

/** Every denoiser, best first: 'auto' takes the first one the device runs. */
export const wavefrontDenoisers: Readonly<Record<WavefrontDenoiserName, WavefrontDenoiserEntry>> = { oidn: oidnDenoiser, atrous: atrousDenoiser };

/** The film records a denoiser reads ('auto', not yet resolved: whatever any of them reads). */
export function denoiserFilmReads(denoiser: WavefrontDenoiseSettings['denoiser']): { aovs: boolean; moments: boolean } {
  const entries = denoiser === 'auto' ? Object.values(wavefrontDenoisers) : [wavefrontDenoisers[denoiser]];
  return { aovs: entries.some((e) => e.reads.aovs), moments: entries.some((e) => e.reads.moments) };
}

/** Resolves `denoiser: 'auto'` in place to the best denoiser the device runs; refuses a named one it cannot. */
export function resolveWavefrontDenoiser(output: { denoise: WavefrontDenoiseSettings | null }, device: GPUDevice): void {
  const requested = output.denoise;
  if (!requested) return;
  if (requested.denoiser === 'auto') {
    const best = Object.values(wavefrontDenoisers).find((d) => d.runsOn(device));
    if (!best) throw new GpuRendererError('INVALID_OPTION', 'no denoiser runs on this device', { field: 'denoise.denoiser' });
    output.denoise = { ...requested, denoiser: best.name };
    return;
  }
  if (!wavefrontDenoisers[requested.denoiser].runsOn(device)) {
    const fallback = Object.values(wavefrontDenoisers).find((d) => d.runsOn(device));
    throw new GpuRendererError('INVALID_OPTION', `this device's limits are below what the '${requested.denoiser}' denoiser needs${fallback ? `; use denoise: '${fallback.name}'` : ''}`, { field: 'denoise.denoiser' });
  }
}

/** Loads and compiles the chosen denoiser (after resolveWavefrontDenoiser); returns its factory. */
export async function prepareWavefrontDenoiser(device: GPUDevice, settings: WavefrontDenoiseSettings, customWeights: Uint8Array | null, features: ShaderFeatures): Promise<WavefrontDenoiserFactory> {
  if (settings.denoiser === 'auto') throw new Error('prepareWavefrontDenoiser: resolve the denoiser first');
  return wavefrontDenoisers[settings.denoiser].prepare(device, settings, customWeights, features);
}
