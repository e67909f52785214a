/* global self */
// A module Worker that path traces the Cornell box into the OffscreenCanvas it was given and
// reports the frame's stats and readPixels() back to the page; then denoises the same frame with
// OIDN (its weights a chunk the bundler split off, loaded in the worker) and reports the means.
import { createCornellBoxScene, createWavefrontPathTracingComputeRenderer } from '@plasius/gpu-renderer';

self.onmessage = async (event) => {
  const { canvas, size, samplesPerPixel } = event.data;
  try {
    const renderer = await createWavefrontPathTracingComputeRenderer({ ...createCornellBoxScene(), canvas, width: size, height: size, samplesPerPixel, maxDepth: 4 });
    const stats = await renderer.renderFrame();
    const pixels = await renderer.readPixels();
    const denoiser = await createWavefrontPathTracingComputeRenderer({ ...createCornellBoxScene(), width: size, height: size, samplesPerPixel, maxDepth: 4, denoise: 'oidn' });
    await denoiser.renderFrame();
    const raw = (await denoiser.readRadiance()).data;
    const denoised = (await denoiser.readDenoised()).data;
    let rawSum = 0, denoisedSum = 0, changed = 0;
    for (let i = 0; i < raw.length; i += 4) {
      rawSum += raw[i] + raw[i + 1] + raw[i + 2];
      denoisedSum += denoised[i] + denoised[i + 1] + denoised[i + 2];
      if (Math.abs(denoised[i + 1] - raw[i + 1]) > 0.01 * (raw[i + 1] + 0.01)) changed++;
    }
    self.postMessage({
      inWorker: typeof document === 'undefined' && typeof self.importScripts === 'function',
      samples: stats.samplesAccumulated,
      rays: stats.rays.total,
      pixels: Array.from(pixels.data),
      oidn: { denoiser: denoiser.getSnapshot().denoise.denoiser, meanRatio: denoisedSum / rawSum, changedShare: changed / (raw.length / 4) },
    });
  } catch (error) {
    self.postMessage({ error: `${error?.code ?? ''} ${error?.message ?? error}` });
  }
};
