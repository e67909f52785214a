import { createWavefrontPathTracingComputeRenderer } from './renderer.ts';
import type { WavefrontFrameStats, WavefrontPathTracingOptions, WavefrontPixelImage, WavefrontRadianceImage } from './types.ts';

export interface WavefrontOneShotResult {
  stats: WavefrontFrameStats;
  radiance: WavefrontRadianceImage;
  pixels: WavefrontPixelImage;
}

/** Compatibility wrapper: create, render `samplesPerPixel` once, read back, destroy. */
export async function renderWavefrontPathTracingComputeFrame(options: WavefrontPathTracingOptions): Promise<WavefrontOneShotResult> {
  const renderer = await createWavefrontPathTracingComputeRenderer(options);
  try {
    const stats = await renderer.renderFrame();
    const radiance = await renderer.readRadiance();
    const pixels = await renderer.readPixels();
    return { stats, radiance, pixels };
  } finally {
    renderer.destroy();
  }
}
