// The renderer's OIDN denoiser (denoise: 'oidn'): on the film as it is (radiance and AOV sums over
// the sample count) it gives the CPU evaluation of the network on readRadiance() and the AOVs; it
// keeps the Cornell box's mean; it beats the a-trous preview against a converged render; and
// `denoise: true` picks it.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { denoiseOidnReference } from '../../../src/film/denoise/oidn/oidn-reference.ts';
import { loadOidnModel } from '../../../src/film/denoise/oidn/weights.ts';
import { displayPeakSignalToNoiseRatio } from '../../../src/film/metrics/display.ts';
import { convergedCornellReference, cornellRenderer } from '../../pathtracer/output-helpers.ts';

const mean = (data: Float32Array, channel: number): number => {
  let s = 0;
  for (let i = channel; i < data.length; i += 4) s += data[i]!;
  return s / (data.length / 4);
};

test("denoise: 'oidn' runs the network on the film: equal to the CPU evaluation on readRadiance and the AOVs; readRadiance stays raw", async () => {
  const renderer = await cornellRenderer(24, { seed: 3, denoise: { denoiser: 'oidn', precision: 'f32' }, aovs: true });
  try {
    await renderer.renderFrame({ samplesPerPixel: 8 });
    const raw = await renderer.readRadiance();
    const before = raw.data.slice();
    const gpu = (await renderer.readDenoised()).data;
    const emission = await renderer.readAov('emission');
    const cpu = denoiseOidnReference(await loadOidnModel('rt_hdr_alb_nrm'), { color: raw, albedo: await renderer.readAov('albedo'), normal: await renderer.readAov('normal'), emission });
    let worst = 0;
    for (let i = 0; i < gpu.length; i++) if (i % 4 !== 3) worst = Math.max(worst, Math.abs(gpu[i]! - cpu[i]!) / (Math.abs(cpu[i]!) + 0.01));
    assert.ok(worst < 1e-4, `worst relative difference ${worst}`);
    assert.deepEqual((await renderer.readRadiance()).data, before, 'readRadiance keeps the raw estimate');
    const snapshot = renderer.getSnapshot().denoise!;
    assert.equal(snapshot.denoiser, 'oidn');
    assert.equal(snapshot.weights, 'rt_hdr_alb_nrm');
    assert.equal(snapshot.auxiliary, true);
  } finally {
    renderer.destroy();
  }
});

test('OIDN keeps the Cornell box mean within 0.5% and beats the a-trous preview against a converged render (4 and 16 spp)', async () => {
  const size = 48;
  const ref = await convergedCornellReference(size);
  // denoise: true picks the better denoiser the device runs: OIDN.
  const oidn = await cornellRenderer(size, { seed: 5, tileSize: 64, denoise: true });
  const atrous = await cornellRenderer(size, { seed: 5, tileSize: 64, denoise: 'atrous' });
  try {
    assert.equal(oidn.getSnapshot().denoise!.denoiser, 'oidn');
    let spp = 0;
    for (const target of [4, 16]) {
      for (const r of [oidn, atrous]) await r.renderFrame({ samplesPerPixel: target - spp });
      spp = target;
      const raw = await oidn.readRadiance();
      const denoised = await oidn.readDenoised();
      for (let c = 0; c < 3; c++) {
        const shift = mean(denoised.data, c) / mean(raw.data, c) - 1;
        assert.ok(Math.abs(shift) < 0.005, `${spp} spp, channel ${c}: mean shift ${(100 * shift).toFixed(2)}%`);
      }
      const psnr = { raw: displayPeakSignalToNoiseRatio(raw, ref), oidn: displayPeakSignalToNoiseRatio(denoised, ref), atrous: displayPeakSignalToNoiseRatio(await atrous.readDenoised(), ref) };
      assert.ok(psnr.oidn > psnr.atrous + 1, `${spp} spp: display PSNR raw ${psnr.raw.toFixed(2)}, a-trous ${psnr.atrous.toFixed(2)}, OIDN ${psnr.oidn.toFixed(2)} dB`);
    }
  } finally {
    oidn.destroy();
    atrous.destroy();
  }
});

test("colour-only OIDN (auxiliary: false) runs the rt_hdr weights; emission: 'network' denoises the whole beauty", async () => {
  const renderer = await cornellRenderer(16, { seed: 4, denoise: { auxiliary: false, precision: 'f32', emission: 'network' } });
  try {
    await renderer.renderFrame({ samplesPerPixel: 4 });
    const raw = await renderer.readRadiance();
    const gpu = (await renderer.readDenoised()).data;
    const cpu = denoiseOidnReference(await loadOidnModel('rt_hdr'), { color: raw });
    for (let i = 0; i < gpu.length; i++) if (i % 4 !== 3) assert.ok(Math.abs(gpu[i]! - cpu[i]!) <= 1e-4 * (Math.abs(cpu[i]!) + 0.01), `value ${i}`);
    assert.equal(renderer.getSnapshot().denoise!.weights, 'rt_hdr');
  } finally {
    renderer.destroy();
  }
});
