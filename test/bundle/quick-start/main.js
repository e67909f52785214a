import { createCornellBoxScene, createWavefrontPathTracingComputeRenderer } from '@plasius/gpu-renderer';

const renderer = await createWavefrontPathTracingComputeRenderer({
  ...createCornellBoxScene(),
  canvas: '#view',
  width: 256,
  height: 256,
  samplesPerPixel: 1,
});
const label = document.querySelector('#samples');
// Each frame adds one sample per pixel; the canvas shows the running mean.
for (let frame = 0; frame < 256; frame++) {
  const stats = await renderer.renderFrame();
  label.textContent = `${stats.samplesAccumulated} samples per pixel, ${(stats.rays.total / stats.wallTimeMs / 1000).toFixed(1)} M rays/s`;
  await new Promise(requestAnimationFrame);
}
