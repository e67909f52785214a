// The render farm on a real Redis (a local redis-server on a free port) and real BullMQ: two worker
// processes and an 8-frame job; one worker is killed mid-frame; every frame arrives exactly once
// (its stalled frame taken over by the other worker) and `farm status` reports completion. Bad
// jobs (unknown asset, bad frame range, unreachable Redis) are typed errors naming the field; a
// frame that keeps failing is retried with backoff, listed as failed, and retried on resubmission.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawn, type ChildProcess } from 'node:child_process';
import { mkdtemp, readdir, readFile, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { NodeIO } from '@gltf-transform/core';
import { decode } from 'fast-png';
import { parseCliArgs } from '../../src/cli/args.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import type { FarmStatus } from '../../src/farm/status.ts';
import { freePort, startRedis } from '../helpers/redis.ts';
import { farm, rejectsWith } from '../helpers/farm-cli.ts';
import { createBendingTube } from '../sequence/fixtures.ts';

const root = fileURLToPath(new URL('../..', import.meta.url));
const cli = join(root, 'src/cli/main.ts');

interface Worker {
  child: ChildProcess;
  log: string;
  exited: Promise<number | null>;
}

function startWorker(redis: string, dir: string): Worker {
  // Short locks so a killed worker's frame is taken over within seconds (production default: 30 s).
  // GPU_RENDERER_CLI_STDERR_COLUMNS marks the CLI's rendering process: the worker renders in the
  // process spawned here (no second one behind it), so SIGKILL stops the renderer itself.
  const env = { ...process.env, GPU_RENDERER_CLI_STDERR_COLUMNS: '' };
  const child = spawn(process.execPath, [cli, 'farm', 'worker', '--redis', redis, '--lock-duration', '2000', '--stalled-interval', '500', '--exit-when-idle', '--output-root', dir, '--asset-root', dir], { stdio: ['ignore', 'ignore', 'pipe'], env });
  const worker: Worker = { child, log: '', exited: new Promise((resolve) => child.on('close', (code) => resolve(code))) };
  child.stderr!.setEncoding('utf8').on('data', (d: string) => (worker.log += d));
  return worker;
}

async function until(condition: () => boolean, what: string, timeoutMs = 120_000): Promise<void> {
  const deadline = Date.now() + timeoutMs;
  while (!condition()) {
    if (Date.now() > deadline) assert.fail(`timed out waiting for ${what}`);
    await new Promise((r) => setTimeout(r, 50));
  }
}

async function writeAsset(dir: string): Promise<string> {
  const path = join(dir, 'tube.glb');
  await writeFile(path, await new NodeIO().writeBinary(createBendingTube().document));
  return path;
}

test('two workers render an 8-frame job; one killed mid-frame, every frame arrives exactly once and status reports completion', async (t) => {
  const redis = await startRedis();
  t.after(() => redis.stop());
  const dir = await mkdtemp(join(tmpdir(), 'gpu-renderer-farm-'));
  t.after(() => rm(dir, { recursive: true, force: true }));
  const asset = await writeAsset(dir);
  const out = join(dir, 'out', 'f-####.png');
  const job = [asset, '--frames', '0-7', '--fps', '8', '--camera', 'Front', '--out', out, '--width', '16', '--height', '16', '--spp', '1', '--max-depth', '1'];
  const submitted = await farm(['submit', ...job, '--redis', redis.url, '--name', 'tube8', '--backoff-ms', '200']);
  assert.equal(submitted.code, 0);
  assert.match(submitted.stdout, /submitted tube8: 8 frames, 8 queued/);

  const a = startWorker(redis.url, dir);
  const b = startWorker(redis.url, dir);
  const workers = [a, b];
  t.after(() => {
    for (const w of workers) if (w.child.exitCode === null) w.child.kill('SIGKILL');
  });
  // Kill worker A as soon as it has a frame in hand (before it can write it).
  await until(() => / started/.test(a.log), 'worker A to start a frame');
  a.child.kill('SIGKILL');
  await a.exited;
  const killedFrame = Number(/frame (\d+) \(tube8 #\d+\) started/.exec(a.log)![1]);
  // A frame that cannot be written (its directory is a file): retried with backoff, then failed.
  await writeFile(join(dir, 'blocker'), 'not a directory');
  const blocked = [asset, '--frames', '3', '--camera', 'Front', '--out', join(dir, 'blocker', 'b-#.png'), '--width', '16', '--height', '16', '--spp', '1', '--max-depth', '1'];
  assert.equal((await farm(['submit', ...blocked, '--redis', redis.url, '--name', 'blocked', '--attempts', '2', '--backoff-ms', '100'])).code, 0);
  assert.equal(await b.exited, 0, b.log);

  const files = (await readdir(join(dir, 'out'))).sort();
  assert.deepEqual(files, Array.from({ length: 8 }, (_, f) => `f-${String(f).padStart(4, '0')}.png`), 'all 8 frames, no temporary files');
  for (const f of files) assert.equal(decode(await readFile(join(dir, 'out', f))).width, 16);
  const writes = [...(a.log + b.log).matchAll(/frame (\d+) \(tube8 #\d+\) wrote /g)].map((m) => Number(m[1])).sort((x, y) => x - y);
  assert.deepEqual(writes, [0, 1, 2, 3, 4, 5, 6, 7], `each frame written once (A: ${a.log}\nB: ${b.log})`);
  assert.doesNotMatch(a.log, / wrote /, 'the killed worker wrote nothing');
  assert.match(b.log, new RegExp(`frame ${killedFrame} \\(tube8 #${killedFrame}\\) wrote `), 'the killed frame was taken over');
  assert.equal((b.log.match(/ loaded /g) ?? []).length, 1, 'the asset is read once per worker');

  const status = await farm(['status', 'tube8', '--json', '--redis', redis.url]);
  const parsed = JSON.parse(status.stdout) as FarmStatus;
  assert.deepEqual(parsed.jobs.map((j) => [j.name, j.frames, j.done, j.failed, j.complete]), [['tube8', 8, 8, 0, true]]);
  assert.deepEqual([parsed.counts.waiting, parsed.counts.active, parsed.counts.completed, parsed.counts.failed], [0, 0, 8, 1]);
  assert.match((await farm(['status', '--redis', redis.url])).stdout, /tube8: 8\/8 frames done \(100%\), complete/);
  // Submitting again finds every frame on disk and enqueues nothing.
  assert.match((await farm(['submit', ...job, '--redis', redis.url, '--name', 'tube8'])).stdout, /8 frames, 0 queued on gpu-renderer, 8 already on disk/);

  assert.match(b.log, /frame 3 \(blocked #0\) failed \(try 1 of 2\)/);
  assert.match(b.log, /frame 3 \(blocked #0\) failed \(try 2 of 2\)/);
  const failed = JSON.parse((await farm(['status', 'blocked', '--json', '--redis', redis.url])).stdout) as FarmStatus;
  assert.deepEqual(failed.jobs.map((j) => [j.done, j.failed, j.remaining, j.complete]), [[0, 1, 0, false]]);
  // Once the cause is gone, submitting the job again retries the failed frame.
  await rm(join(dir, 'blocker'));
  assert.equal((await farm(['submit', ...blocked, '--redis', redis.url, '--name', 'blocked'])).code, 0);
  const c = startWorker(redis.url, dir);
  workers.push(c);
  assert.equal(await c.exited, 0, c.log);
  assert.match(c.log, /frame 3 \(blocked #0\) wrote /);
  const retried = JSON.parse((await farm(['status', 'blocked', '--json', '--redis', redis.url, '--wait', '--timeout', '10'])).stdout) as FarmStatus;
  assert.deepEqual(retried.jobs.map((j) => [j.done, j.failed, j.complete]), [[1, 0, true]]);
});

test('bad jobs: unknown asset, bad frame ranges, bad job files and unreachable Redis are typed errors naming the field', async (t) => {
  const dir = await mkdtemp(join(tmpdir(), 'gpu-renderer-farm-'));
  t.after(() => rm(dir, { recursive: true, force: true }));
  const asset = await writeAsset(dir);
  const closed = `redis://127.0.0.1:${await freePort()}`;
  const out = join(dir, 'f-####.png');
  await rejectsWith(farm(['submit', join(dir, 'missing.glb'), '--frames', '0-7', '--out', out, '--redis', closed]), 'INVALID_OPTION', 'scene', /no asset/);
  assert.throws(() => parseCliArgs(['farm', 'submit', asset, '--frames', '7-0', '--out', out]), (e: unknown) => e instanceof GpuRendererError && e.field === '--frames' && /ends before it starts/.test(e.message));
  await rejectsWith(farm(['submit', asset, '--frames', '0-7', '--out', out, '--redis', closed]), 'QUEUE_UNAVAILABLE', '--redis', /cannot reach Redis/);
  await rejectsWith(farm(['status', '--redis', closed]), 'QUEUE_UNAVAILABLE', '--redis');
  await rejectsWith(farm(['worker', '--redis', closed, '--output-root', dir, '--asset-root', dir]), 'QUEUE_UNAVAILABLE', '--redis');
  await rejectsWith(farm(['status', '--redis', 'http://127.0.0.1:1']), 'INVALID_OPTION', '--redis', /redis:\/\//);
  const saved = process.env.REDIS_URL;
  process.env.REDIS_URL = closed;
  t.after(() => (saved === undefined ? delete process.env.REDIS_URL : (process.env.REDIS_URL = saved)));
  await rejectsWith(farm(['status']), 'QUEUE_UNAVAILABLE', 'REDIS_URL');

  const jobFile = async (json: unknown): Promise<string> => {
    const path = join(dir, 'job.json');
    await writeFile(path, JSON.stringify(json));
    return path;
  };
  await rejectsWith(farm(['submit', await jobFile({ scene: 'tube.glb', frames: '5-2', out: 'f-####.png' })]), 'INVALID_OPTION', '/frames', /ends before it starts/);
  await rejectsWith(farm(['submit', await jobFile({ scene: 'tube.glb', frames: [0, 1, 1], out: 'f-####.png' })]), 'INVALID_OPTION', '/frames', /frame 1 is listed twice/);
  await rejectsWith(farm(['submit', await jobFile({ scene: 'tube.glb', frames: '0-3', out: 'f.png' })]), 'INVALID_OPTION', '/out', /####/);
  await rejectsWith(farm(['submit', await jobFile({ scene: 'tube.glb', frames: '0-3', out: 'f-#.png', colour: 'red' })]), 'INVALID_OPTION', '/colour', /unknown option/);
  await rejectsWith(farm(['submit', await jobFile({ scene: 'nope.glb', frames: '0-3', out: 'f-#.png' })]), 'INVALID_OPTION', '/scene', /no asset/);
  await rejectsWith(farm(['submit', await jobFile({ scene: 'tube.glb', frames: '0-3', out: 'f-#.png', animation: 'Walk' })]), 'INVALID_OPTION', '/animation', /"Walk"/);
});
