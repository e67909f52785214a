// End to end: the demo's raster view. The material swatches, path traced to 16 spp, then drawn by
// createRasterRenderer through the view picker with the same camera, environment and display:
// the raster picture is not blank (its pixels vary) and shows the same scene (its grey values
// correlate with the path-traced ones pixel for pixel), an orbit redraws it, and the page logs no
// error. The Cornell box under its black uniform environment, lit only by its emitter, gets the note
// that the rasteriser has no global illumination instead of a silent black picture.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { join } from 'node:path';
import type { Page } from 'playwright-core';
import { captureAtLeast, captureCanvas, choose, chromiumSkip, correlation, ensureTestOutputDir, grey, meanAbsoluteDifference, openDemo } from './demo-page.ts';

const width = 64;
const height = 48;

const rasterFrames = (tab: Page): Promise<number> =>
  tab.evaluate(() => {
    const el = document.querySelector('[data-readout="samples"]');
    return el?.textContent?.startsWith('raster') ? Number(el.getAttribute('data-value')) : 0;
  });

test('demo: the raster view draws the built-in scene the path tracer shows', { skip: chromiumSkip, timeout: 240_000 }, async (t) => {
  // Under an overcast sky (its suggested exposure puts the scene's own soft box, which the
  // rasteriser cannot light with, far below the sky) both renderers see the same light.
  const { tab, errors, close } = await openDemo(`?scene=swatches&light=sky&sky=overcast&size=${width}x${height}&spf=4&stop=16`);
  t.after(close);

  const traced = await captureAtLeast(tab, 16, 120_000);
  await choose(tab, 'view', 'raster');
  await tab.waitForFunction(() => document.querySelector('[data-readout="samples"]')?.textContent?.startsWith('raster'), undefined, { timeout: 120_000, polling: 50 });
  const raster = await captureCanvas(tab, 'raster');
  assert.deepEqual([raster.width, raster.height], [width, height]);
  const values = grey(raster);
  const mean = values.reduce((s, v) => s + v, 0) / values.length;
  const spread = Math.sqrt(values.reduce((s, v) => s + (v - mean) ** 2, 0) / values.length);
  const r = correlation(raster, traced);
  t.diagnostic(`raster: mean ${mean.toFixed(1)}, standard deviation ${spread.toFixed(1)}; correlation with the path-traced image ${r.toFixed(3)}; status: ${await tab.locator('[data-readout="status"]').textContent()}`);
  await tab.locator('#viewport').screenshot({ path: join(ensureTestOutputDir(), 'demo-swatches-raster.png') });
  assert.ok(spread > 10, `the raster picture is not blank (standard deviation ${spread.toFixed(1)})`);
  assert.ok(r > 0.6, `the raster picture shows the path-traced scene (correlation ${r.toFixed(3)})`);

  // Orbit: the raster view redraws from the new camera.
  const before = await rasterFrames(tab);
  const box = (await tab.locator('#viewport').boundingBox())!;
  await tab.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await tab.mouse.down();
  await tab.mouse.move(box.x + box.width / 2 + 120, box.y + box.height / 2, { steps: 3 });
  await tab.mouse.up();
  await tab.waitForFunction(
    (n) => {
      const el = document.querySelector('[data-readout="samples"]');
      return Number(el?.getAttribute('data-value')) > n;
    },
    before,
    { timeout: 60_000, polling: 50 },
  );
  await tab.waitForTimeout(500);
  const orbited = await captureCanvas(tab, 'raster');
  assert.ok(meanAbsoluteDifference(orbited, raster) > 5, 'the orbited raster view differs');

  // The Cornell box: lit by its emitter only, which the rasteriser does not propagate: a note says so.
  await choose(tab, 'scene', 'cornell');
  await choose(tab, 'environment-source', 'colour');
  await tab.waitForFunction(() => [...document.querySelectorAll('#notes li')].some((li) => li.textContent?.includes('no global illumination')), undefined, { timeout: 60_000 });

  assert.deepEqual(errors, []);
});
