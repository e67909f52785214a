import { test } from 'node:test';
import assert from 'node:assert/strict';
import { parseAovList, parseDuration } from '../../src/film/option-parsing.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';

const isField = (field: string) => (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_OPTION' && e.field === field;

test('parseDuration: units ms, s, m, h, compound parts and bare seconds, in milliseconds', () => {
  assert.equal(parseDuration('30s'), 30_000);
  assert.equal(parseDuration('250ms'), 250);
  assert.equal(parseDuration('1.5m'), 90_000);
  assert.equal(parseDuration('2h'), 7_200_000);
  assert.equal(parseDuration('1h30m'), 5_400_000);
  assert.equal(parseDuration('1m30s500ms'), 90_500);
  assert.equal(parseDuration(' 45 '), 45_000);
  assert.equal(parseDuration('0.5'), 500);
});

test('parseDuration rejects malformed, zero and unit-less garbage with typed errors', () => {
  for (const bad of ['', 's', '30x', '1h 30m', '-5s', '0s', '0', '1e3s', '30s!', 'abc', '.5s']) {
    assert.throws(() => parseDuration(bad), isField('duration'), bad);
  }
  assert.throws(() => parseDuration('x', 'timeLimit'), isField('timeLimit'));
  assert.throws(() => parseDuration(30 as never), isField('duration'));
});

test('parseAovList: comma separated, case-insensitive, de-duplicated, order kept; none and empty give []', () => {
  assert.deepEqual(parseAovList('albedo,normal'), ['albedo', 'normal']);
  assert.deepEqual(parseAovList(' Normal , albedo,normal,depth '), ['normal', 'albedo', 'depth']);
  assert.deepEqual(parseAovList(''), []);
  assert.deepEqual(parseAovList('none'), []);
  assert.deepEqual(parseAovList('albedo,,'), ['albedo']);
  assert.throws(() => parseAovList('albedo,shadow'), isField('aovs'));
  assert.deepEqual(parseAovList('objectid,MaterialId,sampleCount,variance,emission'), ['objectId', 'materialId', 'sampleCount', 'variance', 'emission']);
  assert.throws(() => parseAovList('none,albedo'), isField('aovs'));
  assert.throws(() => parseAovList(undefined as never, 'passes'), isField('passes'));
});
