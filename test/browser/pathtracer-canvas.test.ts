// A real browser: Debian's Chromium (SwiftShader WebGPU) mounts the wavefront path tracer on a
// canvas. An emissive quad filling the view must present its exact radiance, sRGB-encoded, and the
// presented canvas must equal readPixels() of the same renderer.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { decode } from 'fast-png';
import { chromiumSkip, openPackagePage } from './browser-session.ts';
import { linearToSrgb } from '../../src/film/tone-mapping.ts';
import type * as Pkg from '../../src/index.ts';

const size = 32;

test('Chromium: the path tracer presents an emissive quad on a WebGPU canvas exactly', { skip: chromiumSkip }, async (t) => {
  const { tab, pageErrors, close } = await openPackagePage({
    style: `html, body { margin: 0; } canvas { display: block; width: ${size}px; height: ${size}px; }`,
    body: `<canvas id="pt" width="${size}" height="${size}"></canvas>`,
    viewport: { width: 100, height: 100 },
  });
  t.after(close);
  const emission = [0.5, 0.25, 0.05];
  const result = await tab.evaluate(async ({ size, emission }) => {
    const { createWavefrontPathTracingComputeRenderer } = (window as unknown as { pkg: typeof Pkg }).pkg;
    const renderer = await createWavefrontPathTracingComputeRenderer({
      canvas: '#pt', width: size, height: size, maxDepth: 1, samplesPerPixel: 2, toneMapping: 'linear',
      camera: { position: [0, 0, 2], target: [0, 0, 0], fovYDegrees: 40 },
      meshes: [{ positions: [-4, -4, 0, 4, -4, 0, 4, 4, 0, -4, 4, 0], indices: [0, 1, 2, 0, 2, 3], material: { baseColorFactor: [0, 0, 0, 1], emissiveFactor: emission } }],
    });
    const stats = await renderer.renderFrame();
    const pixels = await renderer.readPixels();
    return { samples: stats.samplesAccumulated, pixels: Array.from(pixels.data.slice(0, 4 * size * size)) };
  }, { size, emission });
  assert.deepEqual(pageErrors, []);
  assert.equal(result.samples, 2);
  const expected = emission.map((c) => Math.round(linearToSrgb(c) * 255));
  for (let i = 0; i < size * size; i++) {
    for (let c = 0; c < 3; c++) assert.ok(Math.abs(result.pixels[4 * i + c]! - expected[c]!) <= 1, `readPixels ${i}.${c}: ${result.pixels[4 * i + c]} vs ${expected[c]}`);
  }
  const png = decode(await tab.locator('#pt').screenshot());
  const channels = png.data.length / (png.width * png.height);
  assert.deepEqual([png.width, png.height], [size, size]);
  for (let i = 0; i < size * size; i++) {
    for (let c = 0; c < 3; c++) assert.ok(Math.abs(png.data[i * channels + c]! - expected[c]!) <= 1, `canvas ${i}.${c}: ${png.data[i * channels + c]} vs ${expected[c]}`);
  }
});
