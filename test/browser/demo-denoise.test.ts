// End to end: the demo's denoise toggle. The Cornell box at 16 spp, raw, then with the denoiser
// (the renderer rebuilt with `denoise: true`, the page showing readDenoised()) at the same 16 spp:
// the denoised image's pixel-to-pixel noise (the median absolute difference of adjacent pixels:
// of RGB, over pairs not both black: noise makes most neighbours differ, edges are a minority of
// pairs) is well below the raw one's,
// and its mean brightness
// stays within 10% (the filter moves noise, not energy), and the page logs no error.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { join } from 'node:path';
import { captureAfterRestart, captureAtLeast, chromiumSkip, ensureTestOutputDir, meanValue, medianNeighbourDifference, openDemo, restartsNow } from './demo-page.ts';

const width = 64;
const height = 48;
const samples = 16;

test('demo: the denoise toggle shows a smoother image at equal samples', { skip: chromiumSkip, timeout: 240_000 }, async (t) => {
  const { tab, errors, close } = await openDemo(`?scene=cornell&size=${width}x${height}&spf=4&stop=${samples}`);
  t.after(close);

  // +1 EV (display only, for both): the dim box's noise is then well above 8-bit quantisation.
  await tab.locator('[data-control="exposure"]').fill('1');
  const raw = await captureAtLeast(tab, samples, 120_000);
  const out = ensureTestOutputDir();
  await tab.locator('#viewport').screenshot({ path: join(out, 'demo-cornell-raw.png') });
  const restarts = await restartsNow(tab);
  await tab.locator('[data-control="denoise"]').check();
  const denoised = await captureAfterRestart(tab, restarts, samples, 120_000);
  assert.equal(denoised.samples, raw.samples, 'compared at equal samples');
  await tab.locator('#viewport').screenshot({ path: join(out, 'demo-cornell-denoised.png') });
  const rawNoise = medianNeighbourDifference(raw);
  const denoisedNoise = medianNeighbourDifference(denoised);
  t.diagnostic(`${samples} spp: median adjacent-pixel difference raw ${rawNoise.toFixed(1)}, denoised ${denoisedNoise.toFixed(1)} (8-bit steps); mean raw ${meanValue(raw).toFixed(1)}, denoised ${meanValue(denoised).toFixed(1)}`);
  assert.ok(denoisedNoise < 0.6 * rawNoise, `denoised is smoother: ${denoisedNoise.toFixed(1)} vs raw ${rawNoise.toFixed(1)}`);
  assert.ok(Math.abs(meanValue(denoised) - meanValue(raw)) < 0.1 * meanValue(raw), `mean brightness kept (${meanValue(raw).toFixed(1)} -> ${meanValue(denoised).toFixed(1)})`);

  assert.deepEqual(errors, []);
});
