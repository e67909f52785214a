// The a-trous denoiser (edge-avoiding a-trous, SVGF's spatial filter) against its CPU reference on the
// same inputs; it works on a copy (readRadiance stays raw); flat regions keep their mean within 1%;
// PSNR against a converged render improves; and the 0.2 API's denoise validation helper passes with
// its documented thresholds.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { denoiseAtrousReference } from '../../src/film/denoise/atrous-reference.ts';
import { displayPeakSignalToNoiseRatio } from '../../src/film/metrics/display.ts';
import { defaultDenoiseValidationThresholds, validateWavefrontDenoise } from '../../src/film/denoise/validation.ts';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import { defaultDenoiseSettings } from '../../src/film/denoise/options.ts';
import type { WavefrontPathTracingRenderer } from '../../src/pathtracer/types.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { testDevice } from '../helpers/gpu.ts';
import { convergedCornellReference, cornellRenderer, lambert, meanChannel, rect, squareCamera } from '../pathtracer/output-helpers.ts';

const settings = defaultDenoiseSettings;

async function inputs(renderer: WavefrontPathTracingRenderer) {
  const variance = (await renderer.readAov('variance')).data;
  return {
    radiance: await renderer.readRadiance(),
    albedo: await renderer.readAov('albedo'),
    normal: await renderer.readAov('normal'),
    depth: await renderer.readAov('depth'),
    emission: await renderer.readAov('emission'),
    luminanceVariance: Float32Array.from({ length: variance.length / 4 }, (_, p) => variance[4 * p + 3]!),
  };
}

test('the GPU denoiser equals its CPU reference on the same inputs, and works on a copy', async () => {
  const renderer = await cornellRenderer(24, { seed: 3, denoise: 'atrous', aovs: true });
  try {
    await renderer.renderFrame({ samplesPerPixel: 8 });
    const before = (await renderer.readRadiance()).data.slice();
    const gpu = (await renderer.readDenoised()).data;
    const cpu = denoiseAtrousReference(await inputs(renderer), settings);
    let differs = 0;
    for (let i = 0; i < gpu.length; i++) {
      if (i % 4 === 3) { assert.equal(gpu[i], 1); continue; }
      assert.ok(Math.abs(gpu[i]! - cpu[i]!) <= 2e-3 * Math.abs(cpu[i]!) + 1e-5, `value ${i}: GPU ${gpu[i]}, CPU ${cpu[i]}`);
      if (Math.abs(gpu[i]! - before[i]!) > 1e-3) differs++;
    }
    assert.ok(differs > gpu.length / 4, 'the denoiser changed the image');
    assert.deepEqual((await renderer.readRadiance()).data, before, 'readRadiance keeps the raw estimate');
  } finally {
    renderer.destroy();
  }
});

test("denoising keeps flat regions' mean within 1% (uniform and two-albedo planes under a uniform sky)", async () => {
  const device = await testDevice();
  const size = 32;
  // Under a uniform environment L a Lambertian plane of albedo a has radiance exactly a L: flat
  // regions (noisy estimates of a constant), one per albedo; the seam between them is an albedo edge.
  const renderer = await createWavefrontPathTracingComputeRenderer({
    device, width: size, height: size, tileSize: 32, maxDepth: 3, seed: 11, camera: squareCamera, environment: { color: [1, 0.9, 0.8] }, denoise: 'atrous',
    meshes: [rect(-3, -3, 0, 3, lambert([0.2, 0.3, 0.4])), rect(0, -3, 3, 3, lambert([0.8, 0.7, 0.6]))],
  });
  try {
    let spp = 0;
    for (const target of [4, 16]) {
      await renderer.renderFrame({ samplesPerPixel: target - spp });
      spp = target;
      const raw = (await renderer.readRadiance()).data;
      const denoised = (await renderer.readDenoised()).data;
      for (const half of [{ x: 0, y: 0, w: size / 2, h: size }, { x: size / 2, y: 0, w: size / 2, h: size }]) {
        for (let c = 0; c < 3; c++) {
          const r = meanChannel(raw, size, c, half), d = meanChannel(denoised, size, c, half);
          assert.ok(Math.abs(d / r - 1) < 0.01, `${spp} spp, x >= ${half.x}, channel ${c}: mean ${d} denoised vs ${r} raw`);
        }
      }
      // And the noise is gone: the denoised pixels' spread around the mean is far below the raw one.
      const spread = (data: Float32Array) => {
        const m = meanChannel(data, size, 1, { x: 0, y: 0, w: size / 2 - 2, h: size });
        let s2 = 0;
        for (let y = 0; y < size; y++) for (let x = 0; x < size / 2 - 2; x++) s2 += (data[4 * (y * size + x) + 1]! - m) ** 2;
        return Math.sqrt(s2 / (size * (size / 2 - 2)));
      };
      assert.ok(spread(denoised) < 0.5 * spread(raw), `${spp} spp: spread ${spread(denoised)} denoised vs ${spread(raw)} raw`);
    }
  } finally {
    renderer.destroy();
  }
});

test('denoising improves PSNR against a converged render of the Cornell box and passes the denoise validation helper', async () => {
  const size = 48;
  const ref = await convergedCornellReference(size);
  const renderer = await cornellRenderer(size, { seed: 5, tileSize: 64, denoise: 'atrous' });
  try {
    const stats = await renderer.renderFrame({ samplesPerPixel: 16 });
    const raw = await renderer.readRadiance();
    const denoised = await renderer.readDenoised();
    // PSNR of what a viewer sees (tone mapped, sRGB, 8 bit).
    const psnrRaw = displayPeakSignalToNoiseRatio(raw, ref);
    const psnrDenoised = displayPeakSignalToNoiseRatio(denoised, ref);
    assert.ok(psnrDenoised > psnrRaw + 1.5, `PSNR ${psnrDenoised.toFixed(2)} dB denoised vs ${psnrRaw.toFixed(2)} dB raw`);
    const report = validateWavefrontDenoise({ reference: ref, raw, denoised, invalidSamples: stats.radianceDiagnostics.invalidSamples });
    assert.deepEqual(report.thresholds, defaultDenoiseValidationThresholds);
    assert.ok(report.passed, JSON.stringify(report.criteria.map((c) => [c.id, c.measured, c.threshold])));
  } finally {
    renderer.destroy();
  }
});

test("the a-trous filter keeps the whole image's energy: per channel the denoised total is the raw one (Cornell box with a glossy metal sphere, 4 and 16 spp)", async () => {
  // Without the energy restoration the weighted means lose the bright tail of the noise: -0.7% of
  // this image at 4 spp (-1.9% of the Cornell box at 96x96, -13% of the bench's scene with a glossy
  // metal sphere under a small light).
  const renderer = await cornellRenderer(32, {
    seed: 21,
    tileSize: 32,
    denoise: 'atrous',
    sceneObjects: [{ type: 'sphere', center: [0.333, -0.15, 0.396], radius: 0.25, color: [0.95, 0.85, 0.6], metallic: 1, roughness: 0.12 }],
  });
  try {
    let spp = 0;
    for (const target of [4, 16]) {
      await renderer.renderFrame({ samplesPerPixel: target - spp });
      spp = target;
      const raw = (await renderer.readRadiance()).data;
      const denoised = (await renderer.readDenoised()).data;
      for (let c = 0; c < 3; c++) {
        let r = 0, d = 0;
        for (let i = c; i < raw.length; i += 4) {
          r += raw[i]!;
          d += denoised[i]!;
        }
        assert.ok(Math.abs(d / r - 1) < 1e-4, `${spp} spp, channel ${c}: total ${d} denoised vs ${r} raw (${(100 * (d / r - 1)).toFixed(3)}%)`);
      }
    }
  } finally {
    renderer.destroy();
  }
});

test('the canvas and readPixels show the denoised or the raw image as asked', async () => {
  const denoised = await cornellRenderer(16, { seed: 9, denoise: 'atrous' });
  const raw = await cornellRenderer(16, { seed: 9, denoise: { denoiser: 'atrous', present: 'raw' } });
  const plain = await cornellRenderer(16, { seed: 9 });
  try {
    for (const r of [denoised, raw, plain]) await r.renderFrame({ samplesPerPixel: 4 });
    const a = (await denoised.readPixels()).data, b = (await raw.readPixels()).data, c = (await plain.readPixels()).data;
    assert.deepEqual(b, c, "present: 'raw' shows the accumulation");
    assert.notDeepEqual(a, c);
    assert.equal(denoised.getSnapshot().denoise!.present, 'denoised');
  } finally {
    for (const r of [denoised, raw, plain]) r.destroy();
  }
});

test('bad denoise options and reads are typed errors', async () => {
  const device = await testDevice();
  for (const [denoise, field] of [
    [{ iterations: 0 }, 'denoise.iterations'],
    [{ iterations: 9 }, 'denoise.iterations'],
    [{ sigmaLuminance: 0 }, 'denoise.sigmaLuminance'],
    [{ sigmaDepth: -1 }, 'denoise.sigmaDepth'],
    [{ sigmaNormal: Number.NaN }, 'denoise.sigmaNormal'],
    [{ present: 'both' }, 'denoise.present'],
    [{ strength: 1 }, 'denoise.strength'],
    ['yes', 'denoise'],
    [{ denoiser: 'bilateral' }, 'denoise.denoiser'],
    [{ denoiser: 'oidn', iterations: 3 }, 'denoise.iterations'],
    [{ denoiser: 'atrous', precision: 'f16' }, 'denoise.precision'],
    [{ iterations: 3, auxiliary: false }, 'denoise.auxiliary'],
    [{ precision: 'f8' }, 'denoise.precision'],
    [{ maxMemoryMB: 1 }, 'denoise.maxMemoryMB'],
    [{ auxiliary: 'yes' }, 'denoise.auxiliary'],
    [{ weights: 'rt_hdr.tza' }, 'denoise.weights'],
    [{ weights: new Uint8Array(64) }, 'denoise.weights'],
  ] as const) {
    await assert.rejects(createWavefrontPathTracingComputeRenderer({ device, width: 4, height: 4, denoise } as never), (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_OPTION' && e.field === field, field);
  }
  const renderer = await createWavefrontPathTracingComputeRenderer({ device, width: 4, height: 4 });
  try {
    await assert.rejects(renderer.readDenoised(), (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_STATE' && e.field === 'denoise');
  } finally {
    renderer.destroy();
  }
});
