// Adaptive sampling on the GPU: the per-pixel error equals the CPU computation (Cycles' formula,
// src/film/adaptive) from the same samples; the convergence test's active set equals the
// CPU mask; converged pixels stop receiving samples (per-pixel counts read back) while active ones
// get every pass; an easy region converges at the minimum while a hard one keeps sampling; the
// adaptive image's mean equals a uniform render's within noise; frame budgets and progress events.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { adaptiveConvergedMask, adaptiveSamplingError } from '../../../src/film/adaptive/converged-mask.ts';
import { createWavefrontAdaptiveSamplingLevels } from '../../../src/film/adaptive/sampling-levels.ts';
import { createWavefrontPathTracingComputeRenderer } from '../../../src/pathtracer/index.ts';
import type { WavefrontRenderProgress } from '../../../src/pathtracer/types.ts';
import { GpuRendererError } from '../../../src/errors/gpu-renderer-error.ts';
import { testDevice } from '../../helpers/gpu.ts';
import { cornellRenderer, lambert, perSampleRadiance, rect, squareCamera } from '../../pathtracer/output-helpers.ts';

const SIZE = 16;

/** Full and even-half means after n samples, as RGBA images. */
function estimates(samples: Float64Array[], pixels: number): { full: Float32Array; half: Float32Array } {
  const full = new Float32Array(pixels * 4);
  const half = new Float32Array(pixels * 4);
  for (let p = 0; p < pixels; p++) {
    for (let c = 0; c < 3; c++) {
      let all = 0, even = 0, evens = 0;
      samples.forEach((s, k) => {
        all += s[3 * p + c]!;
        if (k % 2 === 0) { even += s[3 * p + c]!; evens++; }
      });
      full[4 * p + c] = all / samples.length;
      half[4 * p + c] = even / evens;
    }
    full[4 * p + 3] = half[4 * p + 3] = 1;
  }
  return { full, half };
}

test('the GPU error estimate equals the CPU computation (Cycles) from the same samples, and its active set equals the CPU mask', async () => {
  const pixels = SIZE * SIZE;
  const n = 6;
  // No pixel may converge before n samples: every pixel takes every sample, one per frame.
  const probe = await cornellRenderer(SIZE, { seed: 4, adaptiveThreshold: 1e-3, minimumSamplesPerPixel: n, aovs: true });
  let samples: Float64Array[];
  let gpuError: Float32Array;
  try {
    samples = await perSampleRadiance(probe, n);
    gpuError = (await probe.readAov('sampleCount')).data;
  } finally {
    probe.destroy();
  }
  const { full, half } = estimates(samples, pixels);
  const cpuError = new Float64Array(pixels);
  for (let p = 0; p < pixels; p++) {
    cpuError[p] = adaptiveSamplingError(full[4 * p]!, full[4 * p + 1]!, full[4 * p + 2]!, half[4 * p]!, half[4 * p + 1]!, half[4 * p + 2]!);
    assert.equal(gpuError[4 * p]!, n, 'every pixel took every sample');
    const e = gpuError[4 * p + 1]!;
    assert.ok(Math.abs(e - cpuError[p]!) <= 1e-3 * cpuError[p]! + 1e-5, `pixel ${p}: GPU error ${e}, CPU ${cpuError[p]}`);
  }
  // A threshold in the widest gap near the median of the errors: some pixels converge, some not,
  // and none lies within float noise of the threshold.
  const sorted = [...cpuError].sort((a, b) => a - b);
  let best = Math.floor(pixels / 2);
  for (let i = Math.floor(pixels / 4); i < Math.floor((3 * pixels) / 4); i++) if (sorted[i + 1]! / sorted[i]! > sorted[best + 1]! / sorted[best]!) best = i;
  const threshold = Math.sqrt(sorted[best]! * sorted[best + 1]!);
  const mask = adaptiveConvergedMask({ width: SIZE, height: SIZE, data: full }, { width: SIZE, height: SIZE, data: half }, n, { threshold, minimumSamplesPerPixel: n });
  assert.ok(mask.activePixels > 0 && mask.activePixels < pixels, `active ${mask.activePixels}`);

  // The same samples again (same seed: sample numbers are the pixels' counts), tested after n.
  const renderer = await cornellRenderer(SIZE, { seed: 4, adaptiveThreshold: threshold, minimumSamplesPerPixel: n, aovs: true });
  try {
    const first = await renderer.renderFrame({ samplesPerPixel: n });
    assert.equal(first.adaptive!.activePixels, mask.activePixels);
    const before = (await renderer.readAov('sampleCount')).data;
    const second = await renderer.renderFrame({ samplesPerPixel: 1 });
    assert.equal(second.adaptive!.pixelSamples, mask.activePixels, 'one sample per active pixel');
    assert.equal(second.rays.camera, mask.activePixels);
    const after = (await renderer.readAov('sampleCount')).data;
    for (let p = 0; p < pixels; p++) {
      assert.equal(before[4 * p + 2], mask.converged[p] ? 0 : 1, `pixel ${p}: active flag`);
      assert.equal(after[4 * p]! - before[4 * p]!, mask.converged[p] ? 0 : 1, `pixel ${p}: converged pixels take no samples, active ones take one`);
    }
  } finally {
    renderer.destroy();
  }
});

test('an easy region converges at the minimum and stops; a hard one keeps sampling; counts follow the active list', async () => {
  const device = await testDevice();
  // Left half: the uniform environment seen directly (zero variance). Right half: a diffuse square
  // lit by the environment (noisy: half of the light samples fall below its horizon).
  const renderer = await createWavefrontPathTracingComputeRenderer({
    device, width: 24, height: 24, tileSize: 8, maxDepth: 4, seed: 1, camera: squareCamera,
    environment: { color: [0.2, 0.3, 0.4] }, adaptiveThreshold: 0.02, minimumSamplesPerPixel: 4,
    meshes: [rect(0, -1, 1, 1, lambert([0.7, 0.7, 0.7]))],
  });
  try {
    let previous: Float32Array | null = null;
    for (let frame = 0; frame < 4; frame++) {
      const stats = await renderer.renderFrame({ samplesPerPixel: 8 });
      const counts = (await renderer.readAov('sampleCount')).data;
      if (previous) {
        // Passes go only to the pixels in the list. A pixel leaves the list when its 3x3 neighbourhood
        // converged, and a converged pixel changes only when sampled, so reactivation spreads one
        // ring per convergence test: with two tests per frame (8 spp in steps of 4), a pixel whose
        // 5x5 neighbourhood was out of the list at the frame's start takes no sample in it.
        const out = (x: number, y: number) => x < 0 || y < 0 || x >= 24 || y >= 24 || previous![4 * (y * 24 + x) + 2] === 0;
        let checked = 0;
        for (let y = 0; y < 24; y++) {
          for (let x = 0; x < 24; x++) {
            let quiet = true;
            for (let dy = -2; dy <= 2; dy++) for (let dx = -2; dx <= 2; dx++) quiet &&= out(x + dx, y + dy);
            if (!quiet) continue;
            assert.equal(counts[4 * (y * 24 + x)], previous[4 * (y * 24 + x)], `pixel (${x}, ${y})`);
            checked++;
          }
        }
        assert.ok(checked > 50, `${checked} quiet pixels`);
      }
      assert.equal(stats.adaptive!.pixelSamples, stats.rays.camera);
      previous = counts;
    }
    const counts = previous!;
    for (let y = 0; y < 24; y++) {
      for (let x = 0; x < 10; x++) assert.equal(counts[4 * (y * 24 + x)], 4, `sky pixel (${x}, ${y}) stops at the minimum`);
      for (let x = 14; x < 24; x++) assert.ok(counts[4 * (y * 24 + x)]! > 4, `surface pixel (${x}, ${y}) keeps sampling`);
    }
    const snapshot = renderer.getSnapshot();
    assert.ok(snapshot.adaptive!.meanSamplesPerPixel < 32 && snapshot.adaptive!.meanSamplesPerPixel > 4);
  } finally {
    renderer.destroy();
  }
});

test("the adaptive image's mean equals a uniform render's within noise", async () => {
  const adaptive = await cornellRenderer(24, { seed: 7, adaptiveThreshold: 0.05, minimumSamplesPerPixel: 8, aovs: true });
  const uniform = await cornellRenderer(24, { seed: 8, aovs: true });
  try {
    for (let i = 0; i < 4; i++) await adaptive.renderFrame({ samplesPerPixel: 8 });
    const stats = await uniform.renderFrame({ samplesPerPixel: 24 });
    assert.equal(stats.adaptive, null);
    const a = (await adaptive.readRadiance()).data, av = (await adaptive.readAov('variance')).data;
    const u = (await uniform.readRadiance()).data, uv = (await uniform.readAov('variance')).data;
    const counts = (await adaptive.readAov('sampleCount')).data;
    const pixels = 24 * 24;
    let fewer = 0;
    for (let p = 0; p < pixels; p++) if (counts[4 * p]! < 32) fewer++;
    assert.ok(fewer > 0, 'some pixels converged before the ceiling');
    for (let c = 0; c < 3; c++) {
      let ma = 0, mu = 0, va = 0, vu = 0;
      for (let p = 0; p < pixels; p++) {
        ma += a[4 * p + c]!; mu += u[4 * p + c]!;
        va += Number.isFinite(av[4 * p + c]!) ? av[4 * p + c]! : 0; vu += uv[4 * p + c]!;
      }
      const z = (ma - mu) / pixels / Math.sqrt((va + vu) / (pixels * pixels));
      assert.ok(Math.abs(z) < 4, `channel ${c}: z = ${z}`);
    }
  } finally {
    adaptive.destroy();
    uniform.destroy();
  }
});

test('frame budgets: samplesPerPixel is a ceiling, the minimum is guaranteed, renderedSamplesPerPixel reports what ran; progress events', async () => {
  const renderer = await cornellRenderer(16, { seed: 2 });
  const events: WavefrontRenderProgress[] = [];
  const fromOption: WavefrontRenderProgress[] = [];
  renderer.addEventListener('progress', (e) => events.push((e as CustomEvent<WavefrontRenderProgress>).detail));
  try {
    const tight = await renderer.renderFrame({ samplesPerPixel: 64, frameTimeBudgetMs: 0.001, minimumSamplesPerPixel: 3, onProgress: (p) => fromOption.push(p) });
    assert.equal(tight.samplesPerPixel, 64);
    assert.equal(tight.renderedSamplesPerPixel, 3, 'the minimum and nothing more in a budget already spent');
    assert.equal(tight.samplesAccumulated, 3);
    assert.equal(tight.rays.camera, 3 * 256);
    const roomy = await renderer.renderFrame({ samplesPerPixel: 5, frameTimeBudgetMs: 1e6 });
    assert.equal(roomy.renderedSamplesPerPixel, 5);
    assert.equal(roomy.samplesAccumulated, 8);
    assert.ok(events.length >= 2 && fromOption.length >= 1);
    const last = events.at(-1)!;
    assert.equal(last.done, true);
    assert.equal(last.estimatedRemainingMs, 0);
    assert.equal(last.samplesAccumulated, 8);
    for (const e of events) assert.ok(e.elapsedMs >= 0 && e.estimatedRemainingMs >= 0 && e.estimatedTotalMs >= e.elapsedMs);
    // Intermediate events of the budgeted frame come after GPU syncs, with a time estimate.
    const partial = events.filter((e) => !e.done);
    assert.ok(partial.length >= 3, `${partial.length} intermediate events`);
    assert.ok(partial.every((e) => e.samplesThisFrame < e.targetSamplesThisFrame));
    assert.throws(() => renderer.renderOnce({ frameTimeBudgetMs: 5 }), (e: unknown) => e instanceof GpuRendererError && e.field === 'frameTimeBudgetMs');
    // The governor ladder's configs are renderFrame options as they are.
    for (const level of createWavefrontAdaptiveSamplingLevels({ maxSamplesPerPixel: 8, minimumSamplesPerPixel: 2, levels: 3, targetFrameTimeMs: 50 })) {
      const s = await renderer.renderFrame(level.config);
      assert.equal(s.samplesPerPixel, level.config.samplesPerPixel);
      assert.ok(s.renderedSamplesPerPixel >= level.config.minimumSamplesPerPixel && s.renderedSamplesPerPixel <= level.config.samplesPerPixel);
    }
  } finally {
    renderer.destroy();
  }
});

test('renderOnce submits without waiting, also with adaptive sampling; the next renderFrame sees every sample', async () => {
  const renderer = await cornellRenderer(16, { seed: 3, adaptiveThreshold: 0.01, minimumSamplesPerPixel: 16 });
  try {
    renderer.renderOnce({ samplesPerPixel: 4 });
    renderer.renderOnce({ samplesPerPixel: 3 });
    const stats = await renderer.renderFrame({ samplesPerPixel: 2 });
    assert.equal(stats.samplesAccumulated, 9);
    const counts = (await renderer.readAov('sampleCount')).data;
    for (let p = 0; p < 256; p++) assert.equal(counts[4 * p], 9, 'no pixel may converge below the minimum of 16');
    assert.equal(renderer.getSnapshot().adaptive!.meanSamplesPerPixel, 9);
  } finally {
    renderer.destroy();
  }
});

test('bad adaptive and budget options are typed errors naming the field', async () => {
  const device = await testDevice();
  const base = { device, width: 4, height: 4 };
  const cases: [Record<string, unknown>, string][] = [
    [{ adaptiveThreshold: 0 }, 'adaptiveThreshold'],
    [{ adaptiveThreshold: -1 }, 'adaptiveThreshold'],
    [{ adaptiveThreshold: Number.NaN }, 'adaptiveThreshold'],
    [{ adaptiveThreshold: 0.1, minimumSamplesPerPixel: 1 }, 'minimumSamplesPerPixel'],
    [{ adaptiveThreshold: 0.1, minimumSamplesPerPixel: 2.5 }, 'minimumSamplesPerPixel'],
    [{ minimumSamplesPerPixel: 8 }, 'minimumSamplesPerPixel'],
    [{ maxFramePassesPerSubmission: 0 }, 'maxFramePassesPerSubmission'],
    [{ onProgress: 'x' }, 'onProgress'],
  ];
  for (const [options, field] of cases) {
    await assert.rejects(createWavefrontPathTracingComputeRenderer({ ...base, ...options } as never), (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_OPTION' && e.field === field, field);
  }
  const renderer = await createWavefrontPathTracingComputeRenderer(base);
  try {
    for (const [options, field] of [
      [{ frameTimeBudgetMs: 0 }, 'frameTimeBudgetMs'],
      [{ frameTimeBudgetMs: Infinity }, 'frameTimeBudgetMs'],
      [{ minimumSamplesPerPixel: 2 }, 'minimumSamplesPerPixel'],
      [{ samplesPerPixel: 4, frameTimeBudgetMs: 10, minimumSamplesPerPixel: 5 }, 'minimumSamplesPerPixel'],
    ] as const) {
      await assert.rejects(renderer.renderFrame(options as never), (e: unknown) => e instanceof GpuRendererError && e.field === field, field);
    }
  } finally {
    renderer.destroy();
  }
});
