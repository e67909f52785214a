import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createProgressBar, formatDuration } from '../../src/cli/progress.ts';
import { formatRate, formatSummary } from '../../src/cli/render-format.ts';

function stream(isTTY: boolean): { isTTY: boolean; columns: number; text: string; write(t: string): void } {
  return { isTTY, columns: 100, text: '', write(t: string) { this.text += t; } };
}

test('TTY: one line redrawn in place, closed by finish()', () => {
  const s = stream(true);
  let t = 0;
  const bar = createProgressBar(s, 'render', () => t);
  for (let done = 0; done <= 16; done += 4) {
    t += 1000;
    bar.update(done, 16);
  }
  bar.finish();
  assert.equal(s.text.split('\n').length, 2, 'a single line plus the closing newline');
  const frames = s.text.trimEnd().split('\r').filter((x) => x.length > 0);
  assert.equal(frames.length, 5);
  assert.match(frames[0], /\[-+\] 0\/16 spp +0%/);
  assert.match(frames[2], /\[#+-+\] 8\/16 spp {2}50%/);
  assert.match(frames[4], /\[#+\] 16\/16 spp 100%.*done/);
  assert.ok(frames.every((f) => f.endsWith('\x1b[K') && f.length < 100 + 10));
});

test('not a TTY: plain lines, one per 10 % step', () => {
  const s = stream(false);
  const bar = createProgressBar(s, 'render', () => 0);
  for (let done = 0; done <= 100; done++) bar.update(done, 100);
  bar.finish();
  const lines = s.text.trimEnd().split('\n');
  assert.equal(lines.length, 11);
  assert.ok(!s.text.includes('\r') && !s.text.includes('\x1b'));
  assert.match(lines[10], /^render: 100\/100 spp 100%/);
});

test('formatting helpers', () => {
  assert.equal(formatDuration(3.21), '3.2s');
  assert.equal(formatDuration(125), '2m05s');
  assert.equal(formatRate(1234567), '1.23 M');
  assert.equal(formatRate(12), '12.0');
  const text = formatSummary({
    width: 32, height: 32, samplesPerPixel: 4, renderSeconds: 0.5, totalSeconds: 1.5, samplesPerSecond: 8192,
    rays: 20000, raysPerSecond: 40000, invalidSamples: 0, adapter: 'llvmpipe', out: 'x.png',
  });
  assert.match(text, /wrote x\.png \(32x32, 4 spp\)/);
  assert.match(text, /8\.19 ksamples\/s, 40\.0 krays\/s/);
  assert.match(text, /adapter: llvmpipe/);
});
