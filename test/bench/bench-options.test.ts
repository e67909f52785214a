// npm run bench options: command line over environment over bench/baseline.json.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { DEFAULT_ROUNDS, parseBaselineFile, parseBenchOptions } from '../../bench/bench-options.ts';

const file = { ref: 'ca1bff9', description: 'main before the rewrite' };

test('defaults: the ref of bench/baseline.json, default rounds, BVH on', () => {
  const o = parseBenchOptions([], {}, file);
  assert.deepEqual(o.baseline, { enabled: true, ref: 'ca1bff9', source: 'bench/baseline.json', description: 'main before the rewrite' });
  assert.equal(o.rounds, DEFAULT_ROUNDS);
  assert.ok(o.rounds >= 2, 'at least two rounds per version by default');
  assert.equal(o.bvh, true);
});

test('BENCH_BASELINE_REF overrides the file, --baseline overrides both', () => {
  const env = parseBenchOptions([], { BENCH_BASELINE_REF: 'v1' }, file).baseline;
  assert.ok(env.enabled);
  assert.equal(env.ref, 'v1');
  assert.equal(env.source, 'BENCH_BASELINE_REF');
  const o = parseBenchOptions(['--baseline', 'main~3'], { BENCH_BASELINE_REF: 'v1' }, file);
  assert.ok(o.baseline.enabled);
  assert.equal(o.baseline.ref, 'main~3');
  assert.equal(o.baseline.source, 'command line');
});

test('--no-baseline and BENCH_BASELINE=0 switch the baseline off; --baseline wins over the variable', () => {
  assert.equal(parseBenchOptions(['--no-baseline'], {}, file).baseline.enabled, false);
  for (const off of ['0', 'false', 'OFF']) assert.equal(parseBenchOptions([], { BENCH_BASELINE: off }, file).baseline.enabled, false);
  assert.equal(parseBenchOptions([], { BENCH_BASELINE: '1' }, file).baseline.enabled, true);
  assert.equal(parseBenchOptions(['--baseline', 'x'], { BENCH_BASELINE: '0' }, file).baseline.enabled, true);
  assert.equal(parseBenchOptions([], {}, null).baseline.enabled, false, 'no file and no override: no baseline');
});

test('rounds and BVH knobs; bad values are rejected', () => {
  assert.equal(parseBenchOptions(['--rounds', '5'], { BENCH_ROUNDS: '3' }, file).rounds, 5);
  assert.equal(parseBenchOptions([], { BENCH_ROUNDS: '3' }, file).rounds, 3);
  assert.throws(() => parseBenchOptions(['--rounds', '0'], {}, file), /--rounds/);
  assert.throws(() => parseBenchOptions([], { BENCH_ROUNDS: '1.5' }, file), /BENCH_ROUNDS/);
  assert.throws(() => parseBenchOptions(['--bogus'], {}, file));
  assert.equal(parseBenchOptions(['--no-bvh'], {}, file).bvh, false);
  assert.equal(parseBenchOptions([], { BENCH_BVH: '0' }, file).bvh, false);
  assert.equal(parseBenchOptions([], {}, file).pathTracer, true);
  for (const o of [parseBenchOptions(['--bvh-only'], {}, file), parseBenchOptions([], { BENCH_ONLY: 'bvh' }, file)]) {
    assert.equal(o.bvh, true);
    assert.equal(o.pathTracer, false);
  }
  assert.throws(() => parseBenchOptions(['--bvh-only', '--no-bvh'], {}, file), /exclude/);
});

test('glTF knobs: on by default, --no-gltf / BENCH_GLTF=0 skip it, --gltf-only / BENCH_ONLY=gltf run it alone', () => {
  assert.equal(parseBenchOptions([], {}, file).gltf, true);
  assert.equal(parseBenchOptions(['--no-gltf'], {}, file).gltf, false);
  assert.equal(parseBenchOptions([], { BENCH_GLTF: 'off' }, file).gltf, false);
  for (const o of [parseBenchOptions(['--gltf-only'], {}, file), parseBenchOptions([], { BENCH_ONLY: 'gltf' }, file)]) {
    assert.deepEqual([o.gltf, o.bvh, o.pathTracer], [true, false, false]);
  }
  const bvhOnly = parseBenchOptions(['--bvh-only'], {}, file);
  assert.deepEqual([bvhOnly.gltf, bvhOnly.bvh, bvhOnly.pathTracer], [false, true, false]);
  // The command line's --gltf-only wins over BENCH_ONLY=bvh.
  const mixed = parseBenchOptions(['--gltf-only'], { BENCH_ONLY: 'bvh' }, file);
  assert.deepEqual([mixed.gltf, mixed.bvh], [true, false]);
  assert.throws(() => parseBenchOptions(['--gltf-only', '--no-gltf'], {}, file), /exclude/);
  assert.throws(() => parseBenchOptions(['--gltf-only', '--bvh-only'], {}, file), /exclude/);
});

test('GPU knobs: on by default, --no-gpu / BENCH_GPU=0 skip them, --gpu-only / BENCH_ONLY=gpu run them alone', () => {
  assert.equal(parseBenchOptions([], {}, file).gpu, true);
  assert.equal(parseBenchOptions(['--no-gpu'], {}, file).gpu, false);
  assert.equal(parseBenchOptions([], { BENCH_GPU: '0' }, file).gpu, false);
  for (const o of [parseBenchOptions(['--gpu-only'], {}, file), parseBenchOptions([], { BENCH_ONLY: 'gpu' }, file)]) {
    assert.deepEqual([o.gpu, o.bvh, o.gltf, o.raster, o.lighting, o.pathTracer], [true, false, false, false, false, false]);
  }
  assert.equal(parseBenchOptions(['--raster-only'], {}, file).gpu, false);
  assert.throws(() => parseBenchOptions(['--gpu-only', '--no-gpu'], {}, file), /exclude/);
});

test('bench/baseline.json: a ref is required, the description is optional', () => {
  assert.deepEqual(parseBaselineFile('{ "ref": " abc123 " }'), { ref: 'abc123' });
  assert.equal(parseBaselineFile('{ "description": "x" }'), null);
  assert.equal(parseBaselineFile('[]'), null);
  assert.throws(() => parseBaselineFile('{'));
});

test('raster knobs: on by default, --no-raster / BENCH_RASTER=0 skip it, --raster-only / BENCH_ONLY=raster run it alone', () => {
  assert.equal(parseBenchOptions([], {}, file).raster, true);
  assert.equal(parseBenchOptions(['--no-raster'], {}, file).raster, false);
  assert.equal(parseBenchOptions([], { BENCH_RASTER: '0' }, file).raster, false);
  for (const o of [parseBenchOptions(['--raster-only'], {}, file), parseBenchOptions([], { BENCH_ONLY: 'raster' }, file)]) {
    assert.deepEqual([o.raster, o.bvh, o.gltf, o.pathTracer], [true, false, false, false]);
  }
  assert.equal(parseBenchOptions(['--bvh-only'], {}, file).raster, false);
  assert.throws(() => parseBenchOptions(['--raster-only', '--no-raster'], {}, file), /exclude/);
  assert.throws(() => parseBenchOptions(['--raster-only', '--gltf-only'], {}, file), /exclude/);
});

test('output benchmark: opt-in with --output / BENCH_OUTPUT=1, alone with --output-only', () => {
  assert.equal(parseBenchOptions([], {}, file).output, false);
  assert.equal(parseBenchOptions(['--output'], {}, file).output, true);
  assert.equal(parseBenchOptions([], { BENCH_OUTPUT: '1' }, file).output, true);
  assert.equal(parseBenchOptions([], { BENCH_OUTPUT: '0' }, file).output, false);
  const alone = parseBenchOptions(['--output-only'], {}, file);
  assert.deepEqual([alone.output, alone.bvh, alone.gltf, alone.raster, alone.pathTracer], [true, false, false, false, false]);
});

test('browser section: opt-in with --browser / BENCH_BROWSER=1, alone with --browser-only / BENCH_ONLY=browser', () => {
  assert.equal(parseBenchOptions([], {}, file).browser, false);
  assert.equal(parseBenchOptions(['--browser'], {}, file).browser, true);
  assert.equal(parseBenchOptions([], { BENCH_BROWSER: '1' }, file).browser, true);
  assert.equal(parseBenchOptions(['--no-browser'], { BENCH_BROWSER: '1' }, file).browser, false);
  for (const o of [parseBenchOptions(['--browser-only'], {}, file), parseBenchOptions([], { BENCH_ONLY: 'browser' }, file)]) {
    assert.deepEqual([o.browser, o.bvh, o.gltf, o.raster, o.lighting, o.gpu, o.output, o.pathTracer], [true, false, false, false, false, false, false, false]);
  }
});
