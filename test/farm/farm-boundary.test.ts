// The farm's Redis behind a password and TLS, on a local redis-server: `requirepass` refuses a
// wrong or missing password and takes the right one (in the URL or REDIS_URL), which never shows in
// messages or `farm status`; a TLS-only server (`--port 0 --tls-port`, a self-signed certificate
// made by openssl now) is reached by rediss:// once the client trusts the certificate
// (NODE_EXTRA_CA_CERTS), refused without it, and carries a whole round: submit, a worker that
// refuses a job writing outside its root, and status showing why.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawn } from 'node:child_process';
import { mkdir, mkdtemp, readdir, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { NodeIO } from '@gltf-transform/core';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import type { FarmStatus } from '../../src/farm/status.ts';
import { runFarmWorker } from '../../src/farm/worker.ts';
import { redisTlsUnsupported, startRedis } from '../helpers/redis.ts';
import { farm } from '../helpers/farm-cli.ts';
import { createBendingTube } from '../sequence/fixtures.ts';

const cli = fileURLToPath(new URL('../../src/cli/main.ts', import.meta.url));
const password = 'farm-pw-7c1e';

/** `gpu-renderer farm ...` in a process of its own, with `env` added to this one's. */
function farmProcess(args: string[], env: Record<string, string | undefined>): Promise<{ code: number | null; stdout: string; stderr: string }> {
  return new Promise((resolve) => {
    const child = spawn(process.execPath, [cli, 'farm', ...args], { env: { ...process.env, GPU_RENDERER_CLI_STDERR_COLUMNS: '', ...env }, stdio: ['ignore', 'pipe', 'pipe'] });
    let stdout = '';
    let stderr = '';
    child.stdout.setEncoding('utf8').on('data', (d: string) => (stdout += d));
    child.stderr.setEncoding('utf8').on('data', (d: string) => (stderr += d));
    child.on('close', (code) => resolve({ code, stdout, stderr }));
  });
}

async function scratch(t: { after(fn: () => unknown): void }): Promise<{ dir: string; assets: string; frames: string; outside: string; tube: string }> {
  const dir = await mkdtemp(join(tmpdir(), 'gpu-renderer-farm-boundary-'));
  t.after(() => rm(dir, { recursive: true, force: true }));
  const paths = { dir, assets: join(dir, 'assets'), frames: join(dir, 'frames'), outside: join(dir, 'outside'), tube: join(dir, 'assets', 'tube.glb') };
  for (const d of [paths.assets, paths.frames, paths.outside]) await mkdir(d);
  await writeFile(paths.tube, await new NodeIO().writeBinary(createBendingTube().document));
  return paths;
}

const tiny = ['--frames', '0', '--camera', 'Front', '--width', '16', '--height', '16', '--spp', '1', '--max-depth', '1'];

test('Redis with requirepass: a wrong or missing password is refused, the right one (URL or REDIS_URL) works and is never shown', async (t) => {
  const redis = await startRedis({ password });
  t.after(() => redis.stop());
  const { assets, frames, outside, tube } = await scratch(t);
  const host = `127.0.0.1:${redis.port}`;
  for (const url of [`redis://:wrong-pw-93@${host}`, `redis://${host}`]) {
    await assert.rejects(farm(['status', '--redis', url]), (e: unknown) => {
      assert.ok(e instanceof GpuRendererError && e.code === 'QUEUE_UNAVAILABLE' && e.field === '--redis', String(e));
      assert.match(e.message, /WRONGPASS|NOAUTH|invalid username-password/i);
      assert.doesNotMatch(e.message, /wrong-pw-93/, 'the password is not in the message');
      return true;
    });
  }
  const status = await farm(['status', '--redis', redis.url]);
  assert.equal(status.code, 0);
  assert.match(status.stdout, new RegExp(`queue gpu-renderer at redis://:\\*\\*\\*@${host}: 0 waiting`));
  assert.doesNotMatch(status.stdout, new RegExp(password));

  // The whole round through REDIS_URL: submit, a worker (refusing the job that writes outside its root), status.
  const saved = process.env.REDIS_URL;
  process.env.REDIS_URL = redis.url;
  t.after(() => (saved === undefined ? delete process.env.REDIS_URL : (process.env.REDIS_URL = saved)));
  assert.equal((await farm(['submit', tube, ...tiny, '--out', join(outside, 'evil-####.png'), '--name', 'evil'])).code, 0);
  const summary = await runFarmWorker({ outputRoots: [frames], assetRoots: [assets], exitWhenIdle: true, stalledInterval: 500 });
  assert.deepEqual([summary.written, summary.refused], [0, 1]);
  assert.deepEqual(await readdir(outside), []);
  const json = JSON.parse((await farm(['status', '--json'])).stdout) as FarmStatus;
  assert.equal(json.redis, `redis://:***@${host}`);
  assert.deepEqual(json.jobs.map((j) => [j.name, j.failures.map((f) => `${f.code} ${f.field}`)]), [['evil', ['FARM_JOB_REFUSED path']]]);
});

const tlsSkip = redisTlsUnsupported();

test('Redis over TLS only (rediss://, self-signed certificate): trusted through NODE_EXTRA_CA_CERTS it carries submit, worker and status; untrusted or plain it is refused', { skip: tlsSkip }, async (t) => {
  const redis = await startRedis({ tls: true, password });
  t.after(() => redis.stop());
  const { assets, frames, outside, tube } = await scratch(t);
  assert.match(redis.url, /^rediss:\/\//);
  const trusted = { NODE_EXTRA_CA_CERTS: redis.caFile, REDIS_URL: redis.url };

  const untrusted = await farmProcess(['status'], { REDIS_URL: redis.url, NODE_EXTRA_CA_CERTS: undefined });
  assert.notEqual(untrusted.code, 0);
  assert.match(untrusted.stderr, /QUEUE_UNAVAILABLE.*(self[- ]signed|certificate)/i);
  const plain = await farmProcess(['status', '--redis', redis.url.replace('rediss:', 'redis:')], trusted);
  assert.notEqual(plain.code, 0, 'a plain connection to the TLS port is refused');
  assert.match(plain.stderr, /QUEUE_UNAVAILABLE/);

  const submitted = await farmProcess(['submit', tube, ...tiny, '--out', join(outside, 'evil-####.png'), '--name', 'evil'], trusted);
  assert.equal(submitted.code, 0, submitted.stderr);
  const worker = await farmProcess(['worker', '--exit-when-idle', '--stalled-interval', '500', '--output-root', frames, '--asset-root', assets], trusted);
  assert.equal(worker.code, 0, worker.stderr);
  assert.match(worker.stderr, /evil #0 refused: path: .* lies outside the worker's output roots/);
  assert.match(worker.stderr, /stopped; 0 frames written, 0 found done, 0 asset loads, 1 refused \(see farm status\)/);
  assert.deepEqual(await readdir(outside), []);
  const status = await farmProcess(['status', '--json'], trusted);
  assert.equal(status.code, 0, status.stderr);
  const json = JSON.parse(status.stdout) as FarmStatus;
  assert.equal(json.redis, `rediss://:***@127.0.0.1:${redis.port}`);
  assert.deepEqual(json.jobs.map((j) => [j.name, j.failures.map((f) => `${f.code} ${f.field}`)]), [['evil', ['FARM_JOB_REFUSED path']]]);
});
