// Worker CPU time: work on another thread counts, work on the main thread does not; and the timed
// frame of an older harness is found among performance.now() marks by its rounded duration.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { Worker } from 'node:worker_threads';
import { cpuMark, findTimedInterval, isCpuAdapter, workerCpuSeconds } from '../../bench/cpu-clock.ts';
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

const mark = (wallMs: number, processCpuUs = 0): CpuMark => ({ wallMs, processCpuUs, mainThreadCpuUs: 0 });

test('the harness interval enclosing the renderer interval is chosen over an earlier coincidence', () => {
  // 0-2: an unrelated 2.0004 s stretch; 3..6: harness t0, renderer start, renderer end, harness t1.
  const marks = [mark(0), mark(500), mark(2000.4), mark(10_000, 1e6), mark(10_000.05, 1e6), mark(12_000.1, 5e6), mark(12_000.2, 5.2e6)];
  assert.deepEqual(findTimedInterval(marks, 2.0, 0.0005), [3, 6]);
  assert.equal(workerCpuSeconds(marks[3]!, marks[6]!), 4.2);
  assert.deepEqual(findTimedInterval(marks, 2.0, 0.0005, 3), [3, 6], 'also when searching after a previous frame');
  assert.equal(findTimedInterval(marks, 7, 0.0005), null);
  assert.deepEqual(findTimedInterval([mark(1), mark(1001)], 1, 1e-9), [0, 1], 'a single exact candidate');
});

test('CPU adapters are recognised by name', () => {
  assert.ok(isCpuAdapter('mesa / software / llvmpipe-llvm-15 / llvmpipe: Mesa 25.0.7'));
  assert.ok(!isCpuAdapter('nvidia / discrete-gpu / NVIDIA H100'));
  assert.ok(!isCpuAdapter(null));
});
