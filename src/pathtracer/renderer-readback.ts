import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { readAovImage, readMeanRadiance, readRgbaImage } from '../film/accumulation/readback.ts';
import { isWavefrontAovName, wavefrontAovNames, type WavefrontAovName } from '../film/aovs.ts';
import { encodeDenoise } from './frame-passes.ts';
import { readGpuBuffer } from './gpu-buffers.ts';
import { assertUsable, submittedWork, type RendererState } from './renderer-state.ts';
import type { WavefrontPixelImage, WavefrontRadianceImage } from './types.ts';

// The renderer's images, read back once every frame requested before the read has been submitted.

export async function readRadiance(s: RendererState): Promise<WavefrontRadianceImage> {
  await submittedWork(s);
  return readMeanRadiance(s.device, s.resources.film, s.config.width, s.config.height);
}

export async function readDenoised(s: RendererState): Promise<WavefrontRadianceImage> {
  assertUsable(s);
  if (!s.denoiser) throw new GpuRendererError('INVALID_STATE', 'the denoiser is off: create the renderer with denoise: true', { field: 'denoise' });
  await submittedWork(s);
  const encoder = s.device.createCommandEncoder({ label: 'denoise' });
  if (encodeDenoise(s, encoder, null)) s.device.queue.submit([encoder.finish()]);
  return readRgbaImage(s.device, s.resources.denoised, s.config.width, s.config.height);
}

export async function readAov(s: RendererState, name: WavefrontAovName): Promise<WavefrontRadianceImage> {
  assertUsable(s);
  if (!isWavefrontAovName(name)) throw new GpuRendererError('INVALID_OPTION', `unknown AOV ${JSON.stringify(name)} (${wavefrontAovNames.join(', ')})`, { field: 'name' });
  if (name !== 'sampleCount' && !s.config.aovs) throw new GpuRendererError('INVALID_STATE', 'AOVs were not enabled: create the renderer with aovs: true', { field: 'aovs' });
  await submittedWork(s);
  const r = s.resources;
  const adaptive = s.adaptive ? { error: r.adaptiveError, pixels: r.adaptivePixels } : null;
  return readAovImage(s.device, { film: r.film, aovs: r.filmAovs, moments: r.filmMoments, ids: r.filmIds, adaptive }, name, s.config.width, s.config.height, s.instanceIds);
}

export async function readPixels(s: RendererState): Promise<WavefrontPixelImage> {
  await submittedWork(s);
  const { width, height } = s.config;
  const encoder = s.device.createCommandEncoder();
  if (s.display.source === 'denoised') encodeDenoise(s, encoder, null);
  s.display.encodeResolve(encoder, width, height);
  s.device.queue.submit([encoder.finish()]);
  const bytes = await readGpuBuffer(s.device, s.resources.displayPixels, width * height * 4);
  return { width, height, data: new Uint8ClampedArray(bytes) };
}
