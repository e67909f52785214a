import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createWavefrontAdaptiveSamplingLevels } from '../../../src/film/adaptive/sampling-levels.ts';
import { GpuRendererError } from '../../../src/errors/gpu-renderer-error.ts';

test('the ladder runs from the minimum to the maximum, strictly increasing in samples and budget, within bounds', () => {
  for (const max of [1, 2, 3, 7, 16, 64, 1000, 4096]) {
    for (const min of [1, 2, 4]) {
      if (min > max) continue;
      for (const levels of [1, 2, 3, 4, 8, 32]) {
        const target = 20;
        const ladder = createWavefrontAdaptiveSamplingLevels({ maxSamplesPerPixel: max, minimumSamplesPerPixel: min, levels, targetFrameTimeMs: target });
        const where = `max ${max} min ${min} levels ${levels}`;
        assert.ok(ladder.length >= 1 && ladder.length <= levels, where);
        assert.ok(ladder.length <= max - min + 1, where);
        const top = ladder[ladder.length - 1].config;
        assert.equal(top.samplesPerPixel, max, where);
        assert.equal(top.frameTimeBudgetMs, target, where);
        if (levels > 1) assert.equal(ladder[0].config.samplesPerPixel, min, where);
        ladder.forEach((level, i) => {
          const c = level.config;
          assert.ok(Number.isInteger(c.samplesPerPixel) && c.samplesPerPixel >= min && c.samplesPerPixel <= max, where);
          assert.equal(c.minimumSamplesPerPixel, min, where);
          assert.ok(c.minimumSamplesPerPixel <= c.samplesPerPixel);
          assert.ok(c.frameTimeBudgetMs > 0 && c.frameTimeBudgetMs <= target, where);
          // Budget proportional to samples: cost per sample is the same on every level.
          assert.ok(Math.abs(c.frameTimeBudgetMs / c.samplesPerPixel - target / max) < 1e-12, where);
          assert.equal(level.estimatedCostMs, c.frameTimeBudgetMs);
          assert.equal(level.id, `spp-${c.samplesPerPixel}`);
          if (i > 0) {
            assert.ok(c.samplesPerPixel > ladder[i - 1].config.samplesPerPixel, where);
            assert.ok(c.frameTimeBudgetMs > ladder[i - 1].config.frameTimeBudgetMs, where);
          }
        });
      }
    }
  }
});

test('defaults: 4 geometric levels to a 60 Hz frame; enough distinct counts give exactly the levels asked for', () => {
  const ladder = createWavefrontAdaptiveSamplingLevels({ maxSamplesPerPixel: 64 });
  assert.deepEqual(
    ladder.map((l) => l.config.samplesPerPixel),
    [1, 4, 16, 64],
  );
  assert.ok(Math.abs(ladder[3].config.frameTimeBudgetMs - 1000 / 60) < 1e-12);
  assert.ok(Object.isFrozen(ladder) && Object.isFrozen(ladder[0]) && Object.isFrozen(ladder[0].config));
  assert.equal(createWavefrontAdaptiveSamplingLevels({ maxSamplesPerPixel: 512, levels: 10 }).length, 10);
  // Only 2 distinct counts exist between 1 and 2.
  assert.deepEqual(
    createWavefrontAdaptiveSamplingLevels({ maxSamplesPerPixel: 2, levels: 6 }).map((l) => l.config.samplesPerPixel),
    [1, 2],
  );
});

test('invalid options are typed errors naming the field', () => {
  const isField = (field: string) => (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_OPTION' && e.field === field;
  assert.throws(() => createWavefrontAdaptiveSamplingLevels(undefined as never), isField('options'));
  assert.throws(() => createWavefrontAdaptiveSamplingLevels({} as never), isField('maxSamplesPerPixel'));
  assert.throws(() => createWavefrontAdaptiveSamplingLevels({ maxSamplesPerPixel: 0 }), isField('maxSamplesPerPixel'));
  assert.throws(() => createWavefrontAdaptiveSamplingLevels({ maxSamplesPerPixel: 2.5 }), isField('maxSamplesPerPixel'));
  assert.throws(() => createWavefrontAdaptiveSamplingLevels({ maxSamplesPerPixel: 1e6 }), isField('maxSamplesPerPixel'));
  assert.throws(() => createWavefrontAdaptiveSamplingLevels({ maxSamplesPerPixel: 8, minimumSamplesPerPixel: 9 }), isField('minimumSamplesPerPixel'));
  assert.throws(() => createWavefrontAdaptiveSamplingLevels({ maxSamplesPerPixel: 8, levels: 0 }), isField('levels'));
  assert.throws(() => createWavefrontAdaptiveSamplingLevels({ maxSamplesPerPixel: 8, levels: 33 }), isField('levels'));
  assert.throws(() => createWavefrontAdaptiveSamplingLevels({ maxSamplesPerPixel: 8, targetFrameTimeMs: 0 }), isField('targetFrameTimeMs'));
  assert.throws(() => createWavefrontAdaptiveSamplingLevels({ maxSamplesPerPixel: 8, targetFrameTimeMs: Number.NaN }), isField('targetFrameTimeMs'));
});
