// Worker CPU time: work on another thread counts, work on the main thread does not; and the timed
// frame of an older harness is found among performance.now() marks by its rounded duration.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { Worker } from 'node:worker_threads';
import { spawnSync } from 'node:child_process';
import { cpuMark, findTimedInterval, isCpuAdapter, otherLoadCores, workerCpuSeconds } from '../../bench/cpu-clock.ts';
import type { CpuMark } from '../../bench/cpu-clock.ts';

// Spins until the thread itself has used `ms` of CPU, so the amount is fixed however busy the machine is.
const spinSource = (ms: number): string =>
  `const s = process.threadCpuUsage(); while ((process.threadCpuUsage(s).user + process.threadCpuUsage(s).system) < ${ms * 1000}) {}`;

test('CPU used by another thread is counted', async () => {
  const a = cpuMark();
  await new Promise<void>((resolve, reject) => {
    const w = new Worker(spinSource(150), { eval: true });
    w.on('exit', () => resolve());
    w.on('error', reject);
  });
  const b = cpuMark();
  assert.ok(workerCpuSeconds(a, b) >= 0.145, `worker CPU ${workerCpuSeconds(a, b)} s`);
});

test('CPU used by the main thread is not', () => {
  const a = cpuMark();
  new Function(spinSource(150))();
  const b = cpuMark();
  assert.ok((b.mainThreadCpuUs - a.mainThreadCpuUs) / 1e6 >= 0.15);
  assert.ok(workerCpuSeconds(a, b) < 0.075, `worker CPU ${workerCpuSeconds(a, b)} s while only the main thread worked`);
});

const mark = (wallMs: number, processCpuUs = 0): CpuMark => ({ wallMs, processCpuUs, mainThreadCpuUs: 0, machineBusyUs: null });

test('the timed frame is found among many chance matches from time-sliced work', () => {
  // 0..400: a time-sliced build reading the clock every 10 ms (no worker CPU), so many of its pairs
  // last 2.0 s; then harness t0, renderer start, renderer end, harness t1 around a 2.0 s frame.
  const marks: CpuMark[] = [];
  for (let k = 0; k <= 400; k++) marks.push(mark(k * 10));
  const t0 = marks.length;
  marks.push(mark(10_000, 1e6), mark(10_000.05, 1e6), mark(12_000.1, 5e6), mark(12_000.5, 5.2e6));
  const found = findTimedInterval(marks, 2.0, 0.0005);
  assert.deepEqual(found, [t0 + 1, t0 + 2], 'the renderer pair: nothing inside it');
  assert.equal(workerCpuSeconds(marks[found![0]]!, marks[found![1]]!), 4);
  assert.deepEqual(findTimedInterval(marks, 2.0, 0.0005, t0 + 2), null, 'nothing after the frame');
  assert.deepEqual(findTimedInterval(marks, 2.0005, 0.00002), [t0, t0 + 3], 'the harness pair when only it matches');
  assert.equal(findTimedInterval(marks, 1.234, 0.0005), null);
});

test('other processes\' load: machine busy time minus this process\'s, per wall second', () => {
  const from: CpuMark = { wallMs: 1000, processCpuUs: 5e6, mainThreadCpuUs: 0, machineBusyUs: 10e6 };
  const to: CpuMark = { wallMs: 3000, processCpuUs: 6e6, mainThreadCpuUs: 0, machineBusyUs: 14e6 };
  assert.equal(otherLoadCores(from, to), 1.5);
  assert.equal(otherLoadCores({ ...from, machineBusyUs: null }, to), null);
});

test('another process spinning is seen as other load', { skip: process.platform !== 'linux' }, () => {
  const a = cpuMark();
  const child = spawnSync(process.execPath, ['-e', spinSource(300)]);
  assert.equal(child.status, 0);
  const b = cpuMark();
  const othersSeconds = otherLoadCores(a, b)! * ((b.wallMs - a.wallMs) / 1000);
  // At least the child's 0.3 s (less two 10 ms ticks of /proc/stat); other processes only add to it.
  assert.ok(othersSeconds >= 0.28, `other processes' CPU ${othersSeconds} s`);
});

test('CPU adapters are recognised by name', () => {
  assert.ok(isCpuAdapter('mesa / software / llvmpipe-llvm-15 / llvmpipe: Mesa 25.0.7'));
  assert.ok(!isCpuAdapter('nvidia / discrete-gpu / NVIDIA H100'));
  assert.ok(!isCpuAdapter(null));
});
