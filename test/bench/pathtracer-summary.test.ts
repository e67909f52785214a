// Reading both harness formats and the per-scene summary of alternated runs, against values worked
// out by hand from the inputs.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { median, readPathTracerResult, summarizeRuns } from '../../bench/pathtracer-summary.ts';
import type { PathTracerRun, SceneMeasurement } from '../../bench/pathtracer-summary.ts';

test('median of odd and even counts, unsorted input', () => {
  assert.equal(median([3, 1, 2]), 2);
  assert.equal(median([4, 1, 3, 2]), 2.5);
  assert.throws(() => median([]));
});

test('the earlier harness format: samples/s recomputed from resolution, spp and seconds', () => {
  const [m] = readPathTracerResult({
    rows: [{ scene: 'Cornell box', triangles: 36, resolution: '512x512', spp: 8, seconds: 8.332, 'samples/s (M)': 0.252, 'rays/s (M)': 1.198, 'gpu ms': 1, 'BVH build s': 0.8, adapter: 'llvmpipe' }],
  });
  assert.equal(m!.samplesPerSecond, (512 * 512 * 8) / 8.332);
  assert.equal(m!.raysPerSecond, 1.198e6);
  assert.equal(m!.triangles, 36);
  assert.equal(m!.adapter, 'llvmpipe');
  assert.equal(m!.samplesPerWorkerCpuSecond, null, 'no CPU time in that format unless the child runner added it');
});

test('the current harness format: raw per-second figures are taken as they are', () => {
  const [m] = readPathTracerResult({ rows: [{ scene: 'A', resolution: '4x4', spp: 2, seconds: 2, samplesPerSecond: 123.5, raysPerSecond: 456.25, workerCpuSeconds: 4, adapter: 'x' }] });
  assert.equal(m!.samplesPerSecond, 123.5);
  assert.equal(m!.raysPerSecond, 456.25);
  assert.equal(m!.samplesPerWorkerCpuSecond, (4 * 4 * 2) / 4);
});

test('unusable results are rejected with a reason', () => {
  assert.throws(() => readPathTracerResult({}), /no rows/);
  assert.throws(() => readPathTracerResult({ rows: [{ samplesPerSecond: 1 }] }), /scene name/);
  assert.throws(() => readPathTracerResult({ rows: [{ scene: 'A' }] }), /samples\/s/);
});

function m(scene: string, samplesPerSecond: number, extra: Partial<SceneMeasurement> = {}): SceneMeasurement {
  return { scene, triangles: 36, resolution: '8x8', spp: 4, seconds: 1, samplesPerSecond, raysPerSecond: samplesPerSecond * 5, samplesPerWorkerCpuSecond: samplesPerSecond / 2, otherLoadCores: 0.1, adapter: 'gpu', ...extra };
}
const run = (version: 'baseline' | 'current', round: number, scenes: SceneMeasurement[]): PathTracerRun => ({ version, round, childSeconds: 1, scenes });

test('medians per version, ratio of medians, paired ratios per round', () => {
  const scenes = summarizeRuns([
    run('baseline', 1, [m('A', 100), m('B', 10)]),
    run('current', 1, [m('A', 90), m('B', 12)]),
    run('baseline', 2, [m('A', 110), m('B', 10)]),
    run('current', 2, [m('A', 121), m('B', 8)]),
    run('baseline', 3, [m('A', 120), m('B', 10)]),
    run('current', 3, [m('A', 96), m('B', 10)]),
  ]);
  assert.deepEqual(scenes.map((s) => s.scene), ['A', 'B']);
  const [a, b] = scenes;
  assert.equal(a!.baseline!.samplesPerSecond.median, 110);
  assert.equal(a!.current!.samplesPerSecond.median, 96);
  assert.equal(a!.current!.samplesPerSecond.min, 90);
  assert.equal(a!.current!.samplesPerSecond.max, 121);
  assert.equal(a!.samplesPerSecondRatio, 96 / 110);
  assert.equal(a!.raysPerSecondRatio, (96 * 5) / (110 * 5));
  assert.deepEqual(a!.pairedSamplesPerSecondRatios, [90 / 100, 121 / 110, 96 / 120]);
  assert.equal(a!.samplesPerWorkerCpuSecondRatio, 48 / 55);
  assert.deepEqual(a!.pairedSamplesPerWorkerCpuSecondRatios, [45 / 50, 60.5 / 55, 48 / 60]);
  assert.equal(b!.samplesPerSecondRatio, 1);
  assert.equal(a!.current!.otherLoadCores!.median, 0.1);
  assert.equal(a!.mismatch, null);
});

test('a version alone has no ratio; a failed round has no pair; different workloads are flagged', () => {
  const alone = summarizeRuns([run('current', 1, [m('A', 5)]), run('current', 2, [m('A', 7)])]);
  assert.equal(alone[0]!.baseline, null);
  assert.equal(alone[0]!.samplesPerSecondRatio, null);
  assert.equal(alone[0]!.current!.samplesPerSecond.median, 6);

  const partial = summarizeRuns([run('baseline', 1, []), run('current', 1, [m('A', 5)]), run('baseline', 2, [m('A', 4)]), run('current', 2, [m('A', 6)])]);
  assert.deepEqual(partial[0]!.pairedSamplesPerSecondRatios, [6 / 4]);

  const changed = summarizeRuns([run('baseline', 1, [m('A', 5, { spp: 8 })]), run('current', 1, [m('A', 5)])]);
  assert.match(changed[0]!.mismatch ?? '', /spp 8 vs 4/);
});
