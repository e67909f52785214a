/* global self */
// A module Worker that path traces the Cornell box into the OffscreenCanvas it was given and
// reports the frame's stats and readPixels() back to the page.
import { createCornellBoxScene, createWavefrontPathTracingComputeRenderer } from '@plasius/gpu-renderer';

self.onmessage = async (event) => {
  const { canvas, size, samplesPerPixel } = event.data;
  try {
    const renderer = await createWavefrontPathTracingComputeRenderer({ ...createCornellBoxScene(), canvas, width: size, height: size, samplesPerPixel, maxDepth: 4 });
    const stats = await renderer.renderFrame();
    const pixels = await renderer.readPixels();
    self.postMessage({
      inWorker: typeof document === 'undefined' && typeof self.importScripts === 'function',
      samples: stats.samplesAccumulated,
      rays: stats.rays.total,
      pixels: Array.from(pixels.data),
    });
  } catch (error) {
    self.postMessage({ error: `${error?.code ?? ''} ${error?.message ?? error}` });
  }
};
