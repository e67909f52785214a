// A consumer app, as a user writes it: imports the package by name and path traces into a canvas.
// The test bundles this file with esbuild and calls window.renderEmissiveQuad.
import { createWavefrontPathTracingComputeRenderer } from '@plasius/gpu-renderer';

/** An emissive quad filling the view (radiance `emission`, linear display): a known image. */
async function renderEmissiveQuad(canvas, size, emission) {
  const renderer = await createWavefrontPathTracingComputeRenderer({
    canvas,
    width: size,
    height: size,
    maxDepth: 1,
    samplesPerPixel: 2,
    toneMapping: 'linear',
    camera: { position: [0, 0, 2], target: [0, 0, 0], fovYDegrees: 40 },
    meshes: [{ positions: [-4, -4, 0, 4, -4, 0, 4, 4, 0, -4, 4, 0], indices: [0, 1, 2, 0, 2, 3], material: { baseColorFactor: [0, 0, 0, 1], emissiveFactor: emission } }],
  });
  const stats = await renderer.renderFrame();
  const pixels = await renderer.readPixels();
  return { samples: stats.samplesAccumulated, pixels: Array.from(pixels.data) };
}

window.renderEmissiveQuad = renderEmissiveQuad;
window.ready = true;
