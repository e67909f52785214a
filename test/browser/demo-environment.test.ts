// End to end: the demo's environment picker. Choosing an HDRI map (@pmndrs/assets, decoded in the
// browser by loadEnvironmentMap with three's EXRLoader) and then a sun-and-sky preset each rebuilds
// the renderer and changes the image (by far more than the noise between successive captures),
// the HDRI image converges (successive differences shrink as samples accumulate), the sky applies
// its suggested exposure (the exposure control moves far below 0 EV: daylight is in cd/m²) and
// the page logs no error.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { join } from 'node:path';
import { captureAfterRestart, captureAtLeast, choose, chromiumSkip, ensureTestOutputDir, meanAbsoluteDifference, meanValue, openDemo, restartsNow } from './demo-page.ts';

const width = 48;
const height = 36;

test('demo: an HDRI map and a sky preset change the image, converge and log no error', { skip: chromiumSkip, timeout: 300_000 }, async (t) => {
  const { tab, errors, close } = await openDemo(`?scene=swatches&size=${width}x${height}&spf=2&stop=32`);
  t.after(close);

  const uniform = await captureAtLeast(tab, 8, 120_000);

  // HDRI: the studio map.
  let restarts = await restartsNow(tab);
  await choose(tab, 'environment-source', 'hdri');
  const hdri = [];
  for (const spp of [2, 8, 32]) hdri.push(await captureAfterRestart(tab, restarts, spp, 120_000));
  const [a, b, c] = hdri as [typeof uniform, typeof uniform, typeof uniform];
  const early = meanAbsoluteDifference(a, b);
  const late = meanAbsoluteDifference(b, c);
  const fromUniform = meanAbsoluteDifference(b, uniform);
  t.diagnostic(`HDRI: mean ${meanValue(c).toFixed(1)}; |diff| ${a.samples}->${b.samples} spp ${early.toFixed(2)}, ${b.samples}->${c.samples} spp ${late.toFixed(2)}; vs uniform colour ${fromUniform.toFixed(2)}`);
  assert.ok(meanValue(c) > 5, `the HDRI lights the scene (mean ${meanValue(c).toFixed(1)})`);
  assert.ok(late < 0.75 * early, `successive differences shrink: ${early.toFixed(2)} -> ${late.toFixed(2)}`);
  assert.ok(fromUniform > 3 * late, `the HDRI image differs from the uniform-colour image by more than noise (${fromUniform.toFixed(2)} vs ${late.toFixed(2)})`);
  const info = await tab.locator('[data-info="hdri"]').textContent();
  t.diagnostic(`HDRI note: ${info}`);
  assert.match(info ?? '', /^Studio: /);
  const out = ensureTestOutputDir();
  await tab.locator('#viewport').screenshot({ path: join(out, 'demo-swatches-hdri.png') });

  // Another map changes the image again.
  restarts = await restartsNow(tab);
  await choose(tab, 'hdri', 'sunset');
  const sunset = await captureAfterRestart(tab, restarts, 8, 120_000);
  const fromStudio = meanAbsoluteDifference(sunset, b);
  assert.ok(fromStudio > 3 * late, `the sunset map differs from the studio map by more than noise (${fromStudio.toFixed(2)})`);

  // Sun and sky: the clear sky with its suggested exposure.
  restarts = await restartsNow(tab);
  await choose(tab, 'environment-source', 'sky');
  const exposure = Number(await tab.locator('[data-control="exposure"]').inputValue());
  t.diagnostic(`clear sky: suggested exposure ${exposure} EV`);
  assert.ok(exposure < -6, `the sky's suggested exposure is applied (${exposure} EV)`);
  const sky = [await captureAfterRestart(tab, restarts, 8, 120_000), await captureAtLeast(tab, 32, 120_000)];
  const [s8, s32] = sky as [typeof uniform, typeof uniform];
  const fromHdri = meanAbsoluteDifference(s8, sunset);
  t.diagnostic(`sky: mean ${meanValue(s32).toFixed(1)}; |diff| vs sunset map ${fromHdri.toFixed(2)}; 8->32 spp ${meanAbsoluteDifference(s8, s32).toFixed(2)}`);
  assert.ok(meanValue(s32) > 5 && meanValue(s32) < 250, `the sky at its suggested exposure is neither black nor white (mean ${meanValue(s32).toFixed(1)})`);
  assert.ok(fromHdri > 3 * meanAbsoluteDifference(s8, s32), `the sky image differs from the HDRI image by more than noise (${fromHdri.toFixed(2)})`);
  await tab.locator('#viewport').screenshot({ path: join(out, 'demo-swatches-sky.png') });

  assert.deepEqual(errors, []);
});
