// End to end: the demo's noise threshold (adaptive sampling, `adaptiveThreshold`). With a coarse
// threshold on a small Cornell box, pixels converge and stop sampling: the readout's count of
// pixels still sampling falls below the image's pixel count and keeps falling, the loop stops once
// none samples or the stop point is reached, and the page logs no error.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { choose, chromiumSkip, openDemo, restartsNow } from './demo-page.ts';

const width = 32;
const height = 24;

test('demo: the noise threshold turns on adaptive sampling and its readout', { skip: chromiumSkip, timeout: 240_000 }, async (t) => {
  const { tab, errors, close } = await openDemo(`?scene=cornell&size=${width}x${height}&spf=4&stop=512`);
  t.after(close);
  await tab.waitForFunction(() => Number(document.querySelector('[data-readout="samples"]')?.getAttribute('data-value')) >= 4, undefined, { timeout: 120_000 });
  assert.equal(await tab.locator('[data-readout="adaptive"]').isVisible(), false, 'no adaptive readout without a threshold');

  const restarts = await restartsNow(tab);
  await choose(tab, 'noise-threshold', '0.1');
  const active = async (): Promise<number> => Number(await tab.locator('[data-readout="adaptive"]').getAttribute('data-value'));
  await tab.waitForFunction(
    ([r, total]) => {
      const samples = document.querySelector('[data-readout="samples"]');
      const adaptive = document.querySelector('[data-readout="adaptive"]');
      return Number(samples?.getAttribute('data-restarts')) > r! && adaptive?.hasAttribute('data-value') && Number(adaptive.getAttribute('data-value')) < total!;
    },
    [restarts, width * height],
    { timeout: 120_000, polling: 50 },
  );
  const first = await active();
  const text = await tab.locator('[data-readout="adaptive"]').textContent();
  await tab.waitForFunction(() => document.querySelector('[data-readout="samples"]')?.getAttribute('data-idle') === 'true', undefined, { timeout: 180_000, polling: 100 });
  const last = await active();
  const samples = Number(await tab.locator('[data-readout="samples"]').getAttribute('data-value'));
  t.diagnostic(`threshold 0.1: ${first} of ${width * height} pixels sampling (“${text}”), then ${last} when the loop stopped at ${samples} spp`);
  assert.ok(first < width * height, 'some pixels converged');
  assert.ok(last < first, `fewer pixels sample later (${first} -> ${last})`);
  assert.ok(last === 0 || samples >= 512, 'the loop stops once no pixel samples, or at the stop point');
  assert.deepEqual(errors, []);
});
