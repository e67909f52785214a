/* global location */
// A consumer app, as a user writes it: imports the package by name and path traces into a canvas.
// The tests bundle this file (esbuild, webpack) and call window.renderEmissiveQuad and
// window.renderGltf.
import { createWavefrontPathTracingComputeRenderer, loadGltfScene } from '@plasius/gpu-renderer';

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

/**
 * Loads the glTF asset at `url` and path traces it from `camera` (linear display); returns the
 * loaded meshes' vertex streams (tangents included) and the image.
 */
async function renderGltf(canvas, size, url, camera) {
  const scene = await loadGltfScene(new URL(url, location.href));
  const meshes = scene.meshes.map((m) => ({
    positions: Array.from(m.positions),
    normals: Array.from(m.normals ?? []),
    uvs: Array.from(m.uvs ?? []),
    tangents: Array.from(m.tangents ?? []),
    indices: Array.from(m.indices ?? []),
  }));
  const renderer = await createWavefrontPathTracingComputeRenderer({ ...scene, camera, canvas, width: size, height: size, maxDepth: 1, samplesPerPixel: 2, toneMapping: 'linear' });
  const stats = await renderer.renderFrame();
  const pixels = await renderer.readPixels();
  return { meshes, samples: stats.samplesAccumulated, pixels: Array.from(pixels.data) };
}

window.renderEmissiveQuad = renderEmissiveQuad;
window.renderGltf = renderGltf;
window.ready = true;
