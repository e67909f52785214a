import { test } from 'node:test';
import assert from 'node:assert/strict';
import { defaultDenoiseValidationThresholds, validateWavefrontDenoise } from '../../src/film/denoise/validation.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { blotch, blurred, detailRegions, frame, noisy, reference, sceneSize, seam } from './denoise-scenes.ts';

const ref = reference();
const raw = noisy(0.1, 1); // 10% relative noise: relMSE about 0.0095, under the 0.02 default
const run = (denoised: ReturnType<typeof reference>, extra: Partial<Parameters<typeof validateWavefrontDenoise>[0]> = {}, thresholds = {}) =>
  validateWavefrontDenoise({ reference: ref, raw, denoised, invalidSamples: 0, regions: detailRegions, ...extra }, thresholds);

test('a good denoise passes every criterion: identical to the reference, or with 1% residual white noise', () => {
  for (const denoised of [ref, noisy(0.01, 2)]) {
    const report = run(denoised);
    assert.equal(report.passed, true, JSON.stringify(report.criteria));
    assert.deepEqual(
      report.criteria.map((c) => c.id),
      ['structuralArtifacts', 'invalidSamples', 'baselineNoise', 'detailRetention.sheen', 'detailRetention.chrome', 'detailRetention.wood'],
    );
    assert.ok(report.structuralArtifacts.measured < 0.5 * defaultDenoiseValidationThresholds.maxStructuralArtifact);
    for (const region of ['sheen', 'chrome', 'wood']) assert.ok(report.detailRetention[region].measured > 0.95);
  }
  // Identical images: no artifact at all and every region keeps exactly all of its detail.
  const exact = run(ref);
  assert.equal(exact.structuralArtifacts.measured, 0);
  for (const c of Object.values(exact.detailRetention)) assert.ok(Math.abs(c.measured - 1) < 1e-12);
});

test('structural artifacts: a 15% tile seam and a 30% blotch fail; over-smoothing is not an artifact', () => {
  const seamed = run(seam(0.15));
  assert.equal(seamed.structuralArtifacts.passed, false);
  assert.equal(seamed.passed, false);
  // The worst spot lies on the seam: the offset tile's left edge (x = 40, y < 32) or its bottom edge (y = 32, x >= 40).
  const { worstX, worstY } = seamed.structuralArtifacts.details;
  assert.ok((Math.abs(worstX - 39.5) <= 2 && worstY < 34) || (Math.abs(worstY - 31.5) <= 2 && worstX >= 38), `worst at ${worstX}, ${worstY}`);
  // Detail regions are untouched by the seam.
  for (const c of Object.values(seamed.detailRetention)) assert.equal(c.passed, true);
  const blotched = run(blotch(0.3));
  assert.equal(blotched.structuralArtifacts.passed, false);
  assert.ok(Math.abs(blotched.structuralArtifacts.details.worstX - 50) <= 5 && Math.abs(blotched.structuralArtifacts.details.worstY - 15) <= 5);
  // Blur spreads real edges but adds none: the structural criterion passes, the detail one fails.
  const smooth = run(blurred(1));
  assert.equal(smooth.structuralArtifacts.passed, true);
  assert.ok(smooth.structuralArtifacts.measured < 0.001);
});

test('invalid samples: any dropped sample or non-finite pixel fails', () => {
  assert.equal(run(ref, { invalidSamples: 1 }).invalidSamples.passed, false);
  assert.equal(run(ref, { invalidSamples: 1 }).invalidSamples.measured, 1);
  const nan = frame((x, y) => (x === 3 && y === 3 ? Number.NaN : ref.data[4 * (y * sceneSize + x)]));
  const report = run(nan);
  assert.equal(report.invalidSamples.passed, false);
  assert.equal(report.invalidSamples.details.nonFiniteDenoisedPixels, 1);
  const withInfRaw = validateWavefrontDenoise({ reference: ref, raw: frame(() => Infinity), denoised: ref, invalidSamples: 2 });
  assert.equal(withInfRaw.invalidSamples.measured, 2 + sceneSize * sceneSize);
  // A looser threshold is explicit.
  assert.equal(run(ref, { invalidSamples: 3 }, { maxInvalidSamples: 3 }).invalidSamples.passed, true);
});

test('baseline noise: the raw image is measured against the reference; 30% noise fails, 10% passes', () => {
  const ok = run(ref);
  assert.equal(ok.baselineNoise.passed, true);
  // E[relMSE] for relative noise s on values v: s^2 v^2 / (v^2 + 0.01), a little under s^2.
  assert.ok(ok.baselineNoise.measured > 0.008 && ok.baselineNoise.measured < 0.01, `${ok.baselineNoise.measured}`);
  assert.equal(ok.baselineNoise.details.denoiserErrorReduction, Infinity);
  const loud = validateWavefrontDenoise({ reference: ref, raw: noisy(0.3, 4), denoised: noisy(0.01, 5), invalidSamples: 0 });
  assert.equal(loud.baselineNoise.passed, false);
  assert.ok(loud.baselineNoise.measured > 0.07);
  assert.ok(loud.baselineNoise.details.denoiserErrorReduction > 100);
});

test('detail retention: over-smoothing fails per region; per-region thresholds and flat regions', () => {
  const smooth = run(blurred(1));
  for (const region of ['sheen', 'chrome', 'wood']) {
    assert.equal(smooth.detailRetention[region].passed, false, region);
    // Noise is uncorrelated with the reference's detail, so the raw image keeps all of it.
    assert.ok(Math.abs(smooth.detailRetention[region].details.rawRetention - 1) < 0.05);
  }
  const relaxed = run(blurred(1), { regions: [{ ...detailRegions[2], minDetailRetention: 0.05 }] });
  assert.equal(relaxed.detailRetention.wood.threshold, 0.05);
  assert.equal(relaxed.detailRetention.wood.passed, true);
  // A region with no reference detail (inside the flat bright box) cannot show retention: NaN, which fails.
  const flat = run(ref, { regions: [{ name: 'box', x: 14, y: 12, width: 8, height: 8 }] });
  assert.ok(Number.isNaN(flat.detailRetention.box.measured));
  assert.equal(flat.detailRetention.box.passed, false);
  const whole = validateWavefrontDenoise({ reference: ref, raw, denoised: ref, invalidSamples: 0 });
  assert.deepEqual(Object.keys(whole.detailRetention), ['frame']);
});

test('bad input is a typed error naming the field', () => {
  const isField = (field: string) => (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_OPTION' && e.field === field;
  assert.throws(() => validateWavefrontDenoise(null as never), isField('input'));
  assert.throws(() => run(ref, { invalidSamples: -1 }), isField('invalidSamples'));
  assert.throws(() => run(ref, { invalidSamples: 0.5 }), isField('invalidSamples'));
  assert.throws(() => validateWavefrontDenoise({ reference: ref, raw, denoised: { width: 2, height: 2, data: new Float32Array(16) }, invalidSamples: 0 }), isField('denoised'));
  assert.throws(() => run(ref, { regions: [] }), isField('regions'));
  assert.throws(() => run(ref, { regions: [{ name: 'a', x: 60, y: 0, width: 8, height: 8 }] }), isField('regions[0]'));
  assert.throws(() => run(ref, { regions: [detailRegions[0], detailRegions[0]] }), isField('regions[1].name'));
  assert.throws(() => run(ref, {}, { minDetailRetention: -1 }), isField('thresholds.minDetailRetention'));
});
