// A real browser: Debian's Chromium (headless, SwiftShader Vulkan for WebGPU) mounts
// createGpuRenderer on a canvas and the presented pixels must equal the clear colour.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { decode } from 'fast-png';
import { chromiumSkip, openPackagePage } from './browser-session.ts';
import type * as Pkg from '../../src/index.ts';

test('Chromium presents the clear colour on a WebGPU canvas; renderers can be recreated on it', { skip: chromiumSkip }, async (t) => {
  const { tab, pageErrors, close } = await openPackagePage({
    style: 'html, body { margin: 0; background: #fff; } canvas { display: block; width: 64px; height: 48px; }',
    body: '<canvas id="scene" width="64" height="48"></canvas>',
    viewport: { width: 200, height: 120 },
  });
  t.after(close);
  assert.deepEqual(pageErrors, []);
  assert.equal(await tab.evaluate(() => (window as unknown as { pkg: { supportsWebGpu(): Promise<boolean> } }).pkg.supportsWebGpu()), true, 'Chromium exposes a WebGPU adapter');

  /** Every pixel of the canvas as presented (a screenshot of the element), as RGBA bytes. */
  const presented = async (): Promise<{ width: number; height: number; data: Uint8Array }> => {
    const png = decode(await tab.locator('#scene').screenshot());
    return { width: png.width, height: png.height, data: png.data as Uint8Array };
  };
  const assertAll = (image: { width: number; height: number; data: Uint8Array }, rgb: number[], label: string): void => {
    assert.equal(image.width, 64, label);
    assert.equal(image.height, 48, label);
    const channels = image.data.length / (image.width * image.height);
    for (let i = 0; i < image.width * image.height; i++) {
      for (let c = 0; c < 3; c++) {
        const got = image.data[i * channels + c]!;
        if (Math.abs(got - rgb[c]!) > 1) assert.fail(`${label}: pixel ${i} channel ${c} is ${got}, expected ${rgb[c]} (±1)`);
      }
    }
  };

  // 1. Mount by selector, render one frame.
  const first = await tab.evaluate(async () => {
    const { createGpuRenderer } = (window as unknown as { pkg: typeof Pkg }).pkg;
    const renderer = await createGpuRenderer({ canvas: '#scene', clearColor: '#336699' });
    (window as unknown as { renderer: unknown }).renderer = renderer;
    const result = await renderer.renderOnce();
    const s = renderer.getSnapshot();
    return { frameId: result.frameId, target: s.target, format: s.format, width: s.size.width, height: s.size.height };
  });
  assert.equal(first.target, 'canvas');
  assert.equal(first.frameId, 'renderer.realtime.1');
  assert.deepEqual([first.width, first.height], [64, 48]);
  assertAll(await presented(), [0x33, 0x66, 0x99], 'first renderer');

  // 2. Destroy it and mount a new renderer on the same canvas: the old configuration is released.
  await tab.evaluate(async () => {
    const w = window as unknown as { pkg: typeof Pkg; renderer: { destroy(): void } };
    w.renderer.destroy();
    const renderer = await w.pkg.createGpuRenderer({ canvas: document.querySelector('canvas')!, clearColor: [0.8, 0.2, 0.4, 1] });
    await renderer.renderOnce();
    w.renderer = renderer;
  });
  assertAll(await presented(), [204, 51, 102], 'recreated renderer');

  // 3. Lose a shared device for real, then recover with a new renderer on the same canvas.
  const loss = await tab.evaluate(async () => {
    const w = window as unknown as { pkg: typeof Pkg; renderer: { destroy(): void } };
    w.renderer.destroy();
    const adapter = await navigator.gpu.requestAdapter();
    const device = await adapter!.requestDevice();
    let lostReason = '';
    const lost = new Promise<void>((resolve) => {
      void w.pkg
        .createGpuRenderer({ canvas: '#scene', device, clearColor: '#000000', onDeviceLost: (info) => ((lostReason = info.reason), resolve()) })
        .then(async (r) => {
          await r.renderOnce();
          w.renderer = r;
          device.destroy();
        });
    });
    await lost;
    const state = (w.renderer as unknown as { getSnapshot(): { deviceState: string } }).getSnapshot().deviceState;
    const replacement = await w.pkg.createGpuRenderer({ canvas: '#scene', clearColor: '#20c040' });
    await replacement.renderOnce();
    return { lostReason, state };
  });
  assert.deepEqual(loss, { lostReason: 'destroyed', state: 'lost' });
  assertAll(await presented(), [0x20, 0xc0, 0x40], 'renderer after device loss');
  assert.deepEqual(pageErrors, []);
});
