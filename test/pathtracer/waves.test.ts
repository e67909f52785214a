// Waves span pixels x samples: however the frame's work is cut into waves (one sample per wave,
// several samples of every pixel in one wave, or runs that start in the middle of a sample), every
// path gets the same pixel and sample number and the film accumulates the same samples. Each
// path's random numbers depend only on (pixel, sample), so the images agree to float rounding; a
// lost, doubled or misplaced sample (a race between two samples of a pixel in one wave) would not.
// Also: the queues grow to the work of a frame up to their bound, and frames requested without
// awaiting the previous one are submitted at once, in order, and read back labelled.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import type { WavefrontPathTracingRenderer, WavefrontRadianceImage } from '../../src/pathtracer/types.ts';
import { pathRecordLayout } from '../../src/gpu-layout/records.ts';
import { cornellRenderer } from './output-helpers.ts';

function assertClose(a: WavefrontRadianceImage, b: WavefrontRadianceImage, what: string, relative = 2e-5): void {
  assert.equal(a.data.length, b.data.length);
  for (let i = 0; i < a.data.length; i++) {
    const x = a.data[i]!;
    const y = b.data[i]!;
    if (x === y) continue;
    assert.ok(Math.abs(x - y) <= relative * Math.max(1, Math.abs(x), Math.abs(y)), `${what}[${i}]: ${x} vs ${y}`);
  }
}

async function images(r: WavefrontPathTracingRenderer): Promise<Record<string, WavefrontRadianceImage>> {
  return { radiance: await r.readRadiance(), variance: await r.readAov('variance'), albedo: await r.readAov('albedo'), sampleCount: await r.readAov('sampleCount') };
}

test('one wave of 8 samples per pixel, runs starting mid-sample and single-sample waves accumulate the same image', async () => {
  const size = 8;
  const spp = 8;
  // tileSize bounds a wave to tileSize^2 paths: 64 = one sample of the 8x8 image, 100 = runs that
  // cross sample boundaries; by default the wave holds the whole frame (8 samples per pixel).
  const single = await cornellRenderer(size, { seed: 4, aovs: true });
  const crossing = await cornellRenderer(size, { seed: 4, aovs: true, tileSize: 10 });
  const whole = await cornellRenderer(size, { seed: 4, aovs: true, tileSize: undefined, samplesPerPixel: spp });
  try {
    const s = await single.renderFrame({ samplesPerPixel: spp });
    const c = await crossing.renderFrame({ samplesPerPixel: spp });
    const w = await whole.renderFrame();
    assert.deepEqual([s.waves, c.waves, w.waves], [8, Math.ceil((64 * spp) / 100), 1]);
    assert.deepEqual([s.wavePaths, c.wavePaths, w.wavePaths], [64, 100, 64 * spp]);
    for (const stats of [c, w]) {
      assert.deepEqual(stats.rays, s.rays, 'every path traced the same rays');
      assert.deepEqual(stats.terminations, s.terminations);
    }
    const reference = await images(single);
    for (const [name, r] of [['crossing', crossing], ['whole', whole]] as const) {
      const other = await images(r);
      for (const key of Object.keys(reference)) assertClose(other[key]!, reference[key]!, `${name} ${key}`);
    }
    for (let p = 0; p < size * size; p++) assert.equal((await whole.readAov('sampleCount')).data[4 * p], spp);
  } finally {
    single.destroy();
    crossing.destroy();
    whole.destroy();
  }
});

test('adaptive list waves holding several samples of each active pixel match one sample per wave', async () => {
  const options = { seed: 9, adaptiveThreshold: 0.05, minimumSamplesPerPixel: 4, maxDepth: 4 };
  const narrow = await cornellRenderer(16, options);
  const wide = await cornellRenderer(16, { ...options, tileSize: undefined });
  try {
    for (let frame = 0; frame < 3; frame++) {
      const a = await narrow.renderFrame({ samplesPerPixel: 8 });
      const b = await wide.renderFrame({ samplesPerPixel: 8 });
      assert.equal(a.adaptive!.pixelSamples, b.adaptive!.pixelSamples, `frame ${frame}`);
      assert.equal(a.adaptive!.activePixels, b.adaptive!.activePixels, `frame ${frame}`);
      assert.ok(b.waves < a.waves, `${b.waves} wide waves, ${a.waves} narrow`);
    }
    assert.ok(wide.getSnapshot().adaptive!.activePixels < 256, 'some pixels converged');
    assertClose(await wide.readRadiance(), await narrow.readRadiance(), 'radiance');
    // Per pixel the same samples (r) and the same still-sampling flag (b); the error estimate (g)
    // agrees to rounding.
    const [w, n] = [(await wide.readAov('sampleCount')).data, (await narrow.readAov('sampleCount')).data];
    for (let p = 0; p < 256; p++) assert.deepEqual([w[4 * p], w[4 * p + 2]], [n[4 * p], n[4 * p + 2]], `pixel ${p}`);
    assertClose(await wide.readAov('sampleCount'), await narrow.readAov('sampleCount'), 'sampleCount', 1e-4);
  } finally {
    narrow.destroy();
    wide.destroy();
  }
});

test('wave buffers grow to a frame\'s work up to their bound and are reported in the memory stats', async () => {
  const grown = await cornellRenderer(16, { tileSize: undefined, maxDepth: 2 });
  const bounded = await cornellRenderer(16, { maxDepth: 2 });
  try {
    const before = grown.getSnapshot();
    assert.equal(before.tileSize, null);
    assert.equal(before.wavePaths, 256, 'created for one sample of 16x16');
    // lavapipe binds 128 MiB per storage buffer: 2^19 path records of 256 bytes (a discrete GPU: 2^21).
    assert.equal(before.maxWavePaths, Math.min(2 ** 21, Math.floor(grown.device.limits.maxStorageBufferBindingSize / pathRecordLayout.size)));
    const s = await grown.renderFrame({ samplesPerPixel: 6 });
    assert.equal(s.wavePaths, 256 * 6);
    assert.equal(s.waves, 1);
    assert.ok(s.memory.queueBytes >= 256 * 6 * pathRecordLayout.size);
    assert.ok(s.memory.queueBytes > before.memory.queueBytes);
    assert.equal(grown.getSnapshot().memory.queueBytes, s.memory.queueBytes);
    const t = await bounded.renderFrame({ samplesPerPixel: 6 });
    assert.equal(t.wavePaths, 64, 'tileSize 8 bounds a wave to 64 paths');
    assert.equal(t.waves, (256 * 6) / 64);
    assert.equal(bounded.getSnapshot().maxWavePaths, 64);
  } finally {
    grown.destroy();
    bounded.destroy();
  }
});

test('frames requested without awaiting are submitted at once, in order, and their statistics arrive labelled; reads see every frame', async () => {
  const pipelined = await cornellRenderer(16, { seed: 5, maxDepth: 3, tileSize: undefined });
  const sequential = await cornellRenderer(16, { seed: 5, maxDepth: 3, tileSize: undefined, framesInFlight: 1 });
  const device = pipelined.device;
  const submit = device.queue.submit.bind(device.queue);
  const events: string[] = [];
  device.queue.submit = (buffers: Iterable<GPUCommandBuffer>) => {
    events.push('submit');
    submit(buffers);
  };
  try {
    assert.equal(pipelined.getSnapshot().framesInFlight, 2);
    const frames = [1, 2, 3].map(() => pipelined.renderFrame({ samplesPerPixel: 1 }).then((s) => (events.push(`stats ${s.frame}`), s)));
    const stats = await Promise.all(frames);
    device.queue.submit = submit;
    assert.deepEqual(stats.map((s) => [s.frame, s.samplesAccumulated]), [[1, 1], [2, 2], [3, 3]]);
    // Frame 2's work (its waves and its closing submission) reached the queue before frame 1's
    // statistics came back.
    const before = events.slice(0, events.indexOf('stats 1')).filter((e) => e === 'submit').length;
    assert.ok(before >= 4, events.join(', '));
    for (const s of stats) {
      assert.equal(s.rays.camera, 256, `frame ${s.frame}: its own counters`);
      assert.ok(s.gpuTimeMs === null || s.gpuTimeMs > 0);
    }
    // A read requested right after un-awaited frames sees all of them.
    void pipelined.renderFrame({ samplesPerPixel: 1 });
    const image = await pipelined.readRadiance();
    for (let i = 0; i < 4; i++) await sequential.renderFrame({ samplesPerPixel: 1 });
    assertClose(image, await sequential.readRadiance(), 'radiance after 4 frames');
    assert.equal(pipelined.getSnapshot().samplesAccumulated, 4);
  } finally {
    device.queue.submit = submit;
    pipelined.destroy();
    sequential.destroy();
  }
});
