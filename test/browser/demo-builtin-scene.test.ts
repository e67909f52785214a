// End to end: `npm run demo`'s page in Chromium renders the built-in Cornell box progressively.
// Checked: the image converges (the change between successive captures shrinks as samples
// accumulate, as Monte Carlo error does: about 1/2 for captures at 2 -> 8 -> 32 spp), orbiting
// restarts accumulation and changes the view, exposure changes the display without new samples,
// Save PNG downloads exactly the displayed pixels and Save EXR the linear radiance, and the page
// logs no error. The screenshot is kept in test-output/.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFile } from 'node:fs/promises';
import { join } from 'node:path';
import { decode } from 'fast-png';
import { loadEnvironmentMap } from '../../src/lighting/load-environment-map.ts';
import { captureAtLeast, captureNow, chromiumSkip, ensureTestOutputDir, meanAbsoluteDifference, meanValue, openDemo } from './demo-page.ts';

const width = 64;
const height = 48;

test('demo: the built-in Cornell box converges, orbits, re-exposes and saves PNG and EXR', { skip: chromiumSkip, timeout: 240_000 }, async (t) => {
  const { tab, errors, close } = await openDemo(`?scene=cornell&size=${width}x${height}&spf=2&stop=32`);
  t.after(close);

  const captures = [];
  for (const spp of [2, 8, 32]) captures.push(await captureAtLeast(tab, spp, 90_000));
  const [a, b, c] = captures as [typeof captures[0], typeof captures[0], typeof captures[0]];
  assert.deepEqual([a.width, a.height], [width, height]);
  assert.ok(a.samples < b.samples && b.samples < c.samples, `sample counts ${a.samples}, ${b.samples}, ${c.samples}`);
  assert.ok(meanValue(c) > 10, `the Cornell box is lit (mean ${meanValue(c).toFixed(1)})`);
  const early = meanAbsoluteDifference(a, b);
  const late = meanAbsoluteDifference(b, c);
  t.diagnostic(`mean |difference| ${a.samples}->${b.samples} spp: ${early.toFixed(3)}, ${b.samples}->${c.samples} spp: ${late.toFixed(3)} (8-bit steps)`);
  assert.ok(early > 0.5, `the image changes while it accumulates (${early.toFixed(2)})`);
  assert.ok(late < 0.75 * early, `successive differences shrink: ${a.samples}->${b.samples} spp ${early.toFixed(2)}, ${b.samples}->${c.samples} spp ${late.toFixed(2)}`);
  const screenshotDir = ensureTestOutputDir();
  await tab.locator('#viewport').screenshot({ path: join(screenshotDir, 'demo-cornell.png') });

  // Stopped at 32 spp: exposure +1 EV brightens the image at once, keeping the samples.
  await tab.waitForFunction(() => document.querySelector('[data-readout="samples"]')?.getAttribute('data-idle') === 'true');
  await tab.locator('[data-control="exposure"]').fill('1');
  const brighter = await captureNow(tab);
  assert.equal(brighter.samples, c.samples, 'a display change adds or drops no samples');
  assert.ok(meanValue(brighter) > meanValue(c) * 1.15, `+1 EV brightens (${meanValue(c).toFixed(1)} -> ${meanValue(brighter).toFixed(1)})`);

  // Save PNG: the file holds exactly the displayed pixels.
  const [png] = await Promise.all([tab.waitForEvent('download'), tab.locator('[data-control="save-png"]').click()]);
  assert.match(png.suggestedFilename(), /^cornell-box-32spp\.png$/);
  const decoded = decode(await readFile((await png.path())!));
  assert.deepEqual([decoded.width, decoded.height], [width, height]);
  const channels = decoded.data.length / (width * height);
  for (let i = 0; i < width * height; i++) {
    for (let ch = 0; ch < 3; ch++) assert.equal(decoded.data[i * channels + ch], brighter.data[4 * i + ch], `PNG pixel ${i}.${ch}`);
  }
  // Save EXR: linear radiance, read back by an independent decoder (three.js's EXRLoader).
  const [exr] = await Promise.all([tab.waitForEvent('download'), tab.locator('[data-control="save-exr"]').click()]);
  const map = await loadEnvironmentMap(new Uint8Array(await readFile((await exr.path())!)));
  assert.deepEqual([map.width, map.height], [width, height]);
  let lightPixels = 0;
  for (let i = 0; i < width * height; i++) if (map.data[4 * i]! > 1) lightPixels++;
  assert.ok(lightPixels > 0, 'the EXR keeps radiance above 1 (the light), which 8-bit output clips');

  // Orbit: a drag moves the camera, which restarts accumulation and shows another view.
  const box = (await tab.locator('#viewport').boundingBox())!;
  await tab.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await tab.mouse.down();
  await tab.mouse.move(box.x + box.width / 2 + 80, box.y + box.height / 2 + 10, { steps: 4 });
  await tab.mouse.up();
  await tab.waitForFunction((n) => Number(document.querySelector('[data-readout="samples"]')?.getAttribute('data-value')) < n, c.samples, { timeout: 30_000 });
  const orbited = await captureAtLeast(tab, 8, 60_000);
  assert.ok(meanAbsoluteDifference(orbited, b) > 3 * late, 'the orbited view differs from the original view by more than noise');

  assert.deepEqual(errors, []);
});
