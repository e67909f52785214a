// What a farm worker trusts: its roots, path map and origins, never a job. On a real Redis and
// BullMQ, one worker (in this process, real WebGPU) takes a queue of jobs written as an attacker
// with access to Redis would write them: outputs outside the output root (the issue's
// `evil-####.png`, a `..` climb, a link out of the root), scenes outside the asset root (a link),
// glTF references reaching out (relative and absolute), an environment map outside, network origins
// in the job, and data breaking the schema. Every one is refused once (no retries) with
// FARM_JOB_REFUSED naming the job's field, `farm status` shows the reason, nothing is written or
// created outside the roots and no request reaches an origin the worker does not allow; the two
// honest jobs in the same queue (one plain, one through the path map with its buffer on the
// worker's allowed origin) render.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createServer, type Server } from 'node:http';
import { copyFile, mkdir, mkdtemp, readdir, readFile, rm, symlink, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { delimiter, join } from 'node:path';
import { NodeIO } from '@gltf-transform/core';
import { decode } from 'fast-png';
import { parseCliArgs, parseRenderArgs, type RenderCommand } from '../../src/cli/args.ts';
import type { FarmCommand } from '../../src/cli/commands.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { connectRedis, farmKeys, loadBullmq, resolveFarmConnection } from '../../src/farm/connection.ts';
import { farmRenderCommand, frameRenderSettings, type FarmFrameData } from '../../src/farm/farm-job.ts';
import { frameDataLimits, validateFrameData } from '../../src/farm/frame-data-schema.ts';
import type { FarmStatus } from '../../src/farm/status.ts';
import { mapJobPath, parsePathMapping, resolveFarmTrust } from '../../src/farm/worker-trust.ts';
import { runFarmWorker } from '../../src/farm/worker.ts';
import { freePort, startRedis } from '../helpers/redis.ts';
import { capture, farm, rejectsWith } from '../helpers/farm-cli.ts';
import { createBendingTube } from '../sequence/fixtures.ts';

const tiny = ['--camera', 'Front', '--width', '16', '--height', '16', '--spp', '1', '--max-depth', '1'];

/** A frame job's data as `farm submit` would queue it (frame 0), then edited as an attacker likes. */
function frameData(job: string, scene: string, path: string, edit: (render: Record<string, unknown>) => void = () => {}): FarmFrameData {
  const command = farmRenderCommand(parseRenderArgs([scene, '--frames', '0', '--out', path, ...tiny]) as RenderCommand);
  const render = JSON.parse(JSON.stringify(frameRenderSettings(command))) as Record<string, unknown>;
  edit(render);
  return { job, index: 0, path, item: { index: 0, frame: 0, time: 0, variant: undefined, cameraIndex: undefined, cameraName: undefined, turntableCamera: undefined }, render: render as unknown as RenderCommand };
}

/** A server on a loopback port serving `files`, counting every request by path. */
async function serve(files: Record<string, Uint8Array>): Promise<{ server: Server; origin: string; requests: string[] }> {
  const requests: string[] = [];
  const server = createServer((req, res) => {
    requests.push(req.url ?? '');
    const body = files[req.url ?? ''];
    res.writeHead(body === undefined ? 404 : 200, { 'content-type': 'application/octet-stream' });
    res.end(body);
  });
  const port = await freePort();
  await new Promise<void>((resolve) => server.listen(port, '127.0.0.1', resolve));
  return { server, origin: `http://127.0.0.1:${port}`, requests };
}

/** Writes the tube as .gltf + .bin in `dir` and returns the JSON, for references to be edited. */
async function gltfWithBuffer(dir: string, name: string): Promise<{ json: { buffers: { uri: string }[] }; bin: Uint8Array }> {
  const io = new NodeIO();
  const { json, resources } = await io.writeJSON(createBendingTube().document);
  const uri = json.buffers![0]!.uri!;
  await writeFile(join(dir, `${name}.bin`), resources[uri]!);
  return { json: json as unknown as { buffers: { uri: string }[] }, bin: resources[uri]! };
}

test('a worker refuses every job reaching outside its roots or origins, with nothing written outside, and renders the honest ones', async (t) => {
  const redis = await startRedis();
  t.after(() => redis.stop());
  const dir = await mkdtemp(join(tmpdir(), 'gpu-renderer-farm-trust-'));
  t.after(() => rm(dir, { recursive: true, force: true }));
  const assets = join(dir, 'assets');
  const frames = join(dir, 'frames');
  const outside = join(dir, 'outside');
  for (const d of [assets, frames, outside]) await mkdir(d);
  const tube = join(assets, 'tube.glb');
  await writeFile(tube, await new NodeIO().writeBinary(createBendingTube().document));
  // Links inside the roots that lead out of them.
  await symlink(outside, join(frames, 'link'));
  await mkdir(join(outside, 'models'));
  await copyFile(tube, join(outside, 'models', 'tube.glb'));
  await symlink(join(outside, 'models'), join(assets, 'linked'));
  await writeFile(join(outside, 'sky.hdr'), 'not read');
  // glTF assets in the asset root whose buffer lies outside it: by `..`, by absolute path, on an origin the worker does not allow.
  const { json, bin } = await gltfWithBuffer(outside, 'tube');
  const allowed = await serve({ '/tube.bin': bin });
  const forbidden = await serve({ '/tube.bin': bin });
  t.after(() => void allowed.server.close());
  t.after(() => void forbidden.server.close());
  const withBuffer = async (name: string, uri: string): Promise<string> => {
    const path = join(assets, `${name}.gltf`);
    await writeFile(path, JSON.stringify({ ...json, buffers: [{ ...json.buffers[0], uri }] }));
    return path;
  };
  const climbs = await withBuffer('climbs', '../outside/tube.bin');
  const absolute = await withBuffer('absolute', join(outside, 'tube.bin'));
  await withBuffer('remote', `${allowed.origin}/tube.bin`);
  const forbiddenRemote = await withBuffer('forbidden', `${forbidden.origin}/tube.bin`);

  // Submitted as anyone may submit: `farm submit` knows nothing of the workers' roots.
  const submit = async (name: string, scene: string, out: string, extra: string[] = []): Promise<void> => {
    const result = await farm(['submit', scene, '--frames', '0', '--out', out, ...tiny, ...extra, '--redis', redis.url, '--name', name, '--backoff-ms', '100']);
    assert.equal(result.code, 0, result.stderr);
  };
  await submit('ok', tube, join(frames, 'ok-####.png'));
  await submit('evil', tube, join(outside, 'evil-####.png'));
  await submit('evil-new-dir', tube, join(outside, 'made', 'evil-####.png'));
  await submit('link-out', tube, join(frames, 'link', 'linked-####.png'));
  await submit('linked-scene', join(assets, 'linked', 'tube.glb'), join(frames, 'linked-scene-####.png'));
  // Written into the queue directly, as the CLI would never write them.
  const { Queue } = await loadBullmq();
  const queue = new Queue('gpu-renderer', { connection: { url: redis.url } });
  t.after(() => queue.close());
  const inject = async (data: unknown, id: string): Promise<void> => {
    await queue.add('frame', data, { jobId: id, attempts: 3, backoff: { type: 'fixed', delay: 100 }, removeOnComplete: false, removeOnFail: false });
  };
  const injected: [string, FarmFrameData][] = [
    ['climb', frameData('climb', tube, `${frames}/../outside/climb-0000.png`)],
    ['ref-climbs', frameData('ref-climbs', climbs, join(frames, 'climbs-0000.png'))],
    ['ref-absolute', frameData('ref-absolute', absolute, join(frames, 'absolute-0000.png'))],
    ['env-outside', frameData('env-outside', tube, join(frames, 'env-0000.png'), (r) => void (r.env = join(outside, 'sky.hdr')))],
    ['origins', frameData('origins', forbiddenRemote, join(frames, 'origins-0000.png'), (r) => void (r.allowedOrigins = [forbidden.origin]))],
    ['ref-remote', frameData('ref-remote', forbiddenRemote, join(frames, 'remote-0000.png'))],
    ['unknown-key', frameData('unknown-key', tube, join(frames, 'unknown-0000.png'), (r) => void (r.colour = 'red'))],
    ['long-name', frameData('long-name', tube, join(frames, 'long-0000.png'), (r) => void (r.camera = 'x'.repeat(1000)))],
    // Through the path map: the submitting machine's /mnt/studio, where the longest FROM must win.
    ['mapped', frameData('mapped', '/mnt/studio/assets/remote.gltf', '/mnt/studio/frames/mapped-0000.png')],
  ];
  // Each with the job record `farm submit` makes, so `farm status` lists it.
  const records = await connectRedis(resolveFarmConnection({ redis: redis.url }));
  for (const [name, data] of injected) {
    const keys = farmKeys('gpu-renderer', name);
    await records.hset(keys.job, 'name', name, 'scene', data.render.scenePath!, 'out', data.path, 'frames', 1, 'submittedAt', new Date().toISOString(), 'attempts', 3);
    await records.zadd(keys.jobs, Date.now(), name);
    await inject(data, `${name}.0`);
  }
  await records.quit();
  await inject({ job: '../../etc', index: -1 }, 'malformed.0');

  const log = capture();
  const summary = await runFarmWorker({
    redis: redis.url,
    outputRoots: [frames],
    assetRoots: [assets],
    pathMap: [{ from: '/mnt/studio', to: outside }, { from: '/mnt/studio/assets', to: assets }, { from: '/mnt/studio/frames', to: frames }],
    allowedOrigins: [allowed.origin],
    exitWhenIdle: true,
    stalledInterval: 500,
    log,
  });
  assert.equal(summary.written, 2, log.text);
  assert.equal(summary.refused, 13, 'every hostile job, the malformed one included');

  // The honest jobs rendered: the plain one, and the mapped one with its buffer from the allowed origin.
  assert.equal(decode(await readFile(join(frames, 'ok-0000.png'))).width, 16);
  assert.equal(decode(await readFile(join(frames, 'mapped-0000.png'))).width, 16);
  assert.deepEqual(allowed.requests, ['/tube.bin']);
  // Nothing reached the origin the worker does not allow, nothing was written or made outside.
  assert.deepEqual(forbidden.requests, [], 'no request to an origin only a job allowed');
  assert.deepEqual((await readdir(outside)).sort(), ['models', 'sky.hdr', 'tube.bin']);
  assert.deepEqual(await readdir(join(outside, 'models')), ['tube.glb']);
  assert.deepEqual((await readdir(frames)).sort(), ['link', 'mapped-0000.png', 'ok-0000.png'], 'no partial files in the output root');

  const status = JSON.parse((await farm(['status', '--json', '--redis', redis.url])).stdout) as FarmStatus;
  const reasons = Object.fromEntries(status.jobs.map((j) => [j.name, j.failures.map((f) => `${f.code} ${f.field}`)]));
  assert.deepEqual(reasons, {
    'ok': [],
    'evil': ['FARM_JOB_REFUSED path'],
    'evil-new-dir': ['FARM_JOB_REFUSED path'],
    'link-out': ['FARM_JOB_REFUSED path'],
    'linked-scene': ['FARM_JOB_REFUSED render.scenePath'],
    'climb': ['FARM_JOB_REFUSED path'],
    'ref-climbs': ['FARM_JOB_REFUSED render.scenePath'],
    'ref-absolute': ['FARM_JOB_REFUSED render.scenePath'],
    'env-outside': ['FARM_JOB_REFUSED render.env'],
    'origins': ['FARM_JOB_REFUSED render.allowedOrigins'],
    'ref-remote': ['FARM_JOB_REFUSED render.scenePath'],
    'unknown-key': ['FARM_JOB_REFUSED render.colour'],
    'long-name': ['FARM_JOB_REFUSED render.camera'],
    'mapped': [],
  }, log.text);
  assert.deepEqual(status.malformed.map((f) => [f.queueJob, f.code, f.field]), [['malformed.0', 'FARM_JOB_REFUSED', 'job']]);
  // Refused once: a refusal is not retried (the same data would be refused again).
  for (const name of Object.keys(reasons).filter((n) => n !== 'ok' && n !== 'mapped')) {
    const job = await queue.getJob(`${name}.0`);
    assert.equal(job?.attemptsMade, 1, `${name} tried once`);
  }
  // `farm status` shows why, naming the field and the root.
  const text = (await farm(['status', '--redis', redis.url])).stdout;
  assert.match(text, /evil: 0\/1 frames done \(0%\), 1 failed -> .*evil-####\.png\n {2}#0 FARM_JOB_REFUSED at path: ".*evil-0000\.png" lies outside the worker's output roots/);
  assert.match(text, /origins: .*\n {2}#0 FARM_JOB_REFUSED at render\.allowedOrigins: network origins are the worker's own setting/);
  assert.match(text, /ref-climbs: .*\n {2}#0 FARM_JOB_REFUSED at render\.scenePath: the asset's references reach outside/);
  assert.match(text, /refused queue job malformed\.0 FARM_JOB_REFUSED at job/);
});

test('a worker without an output root or an asset root does not start; the roots also come from the environment', async (t) => {
  const dir = await mkdtemp(join(tmpdir(), 'gpu-renderer-farm-trust-'));
  t.after(() => rm(dir, { recursive: true, force: true }));
  const closed = `redis://127.0.0.1:${await freePort()}`;
  // Refused before Redis is asked: the error is about the roots, not the (closed) queue.
  await rejectsWith(runFarmWorker({ redis: closed }), 'INVALID_OPTION', '--output-root', /GPU_RENDERER_FARM_OUTPUT_ROOTS/);
  await rejectsWith(runFarmWorker({ redis: closed, outputRoots: [dir] }), 'INVALID_OPTION', '--asset-root', /GPU_RENDERER_FARM_ASSET_ROOTS/);
  await rejectsWith(runFarmWorker({ redis: closed, outputRoots: [join(dir, 'missing')], assetRoots: [dir] }), 'INVALID_OPTION', '--output-root', /cannot use/);
  await rejectsWith(farm(['worker', '--redis', closed]), 'INVALID_OPTION', '--output-root');
  await rejectsWith(farm(['worker', '--redis', closed, '--output-root', dir]), 'INVALID_OPTION', '--asset-root');
  // With roots it goes on to Redis (closed here).
  await rejectsWith(farm(['worker', '--redis', closed, '--output-root', dir, '--asset-root', dir]), 'QUEUE_UNAVAILABLE', '--redis');
  const saved = { out: process.env.GPU_RENDERER_FARM_OUTPUT_ROOTS, assets: process.env.GPU_RENDERER_FARM_ASSET_ROOTS };
  t.after(() => {
    for (const [key, value] of [['GPU_RENDERER_FARM_OUTPUT_ROOTS', saved.out], ['GPU_RENDERER_FARM_ASSET_ROOTS', saved.assets]] as const) {
      if (value === undefined) delete process.env[key];
      else process.env[key] = value;
    }
  });
  process.env.GPU_RENDERER_FARM_OUTPUT_ROOTS = dir;
  process.env.GPU_RENDERER_FARM_ASSET_ROOTS = dir;
  await rejectsWith(farm(['worker', '--redis', closed]), 'QUEUE_UNAVAILABLE', '--redis');
  // A job cannot carry origins: `farm submit --allow-origin` is refused at once.
  await writeFile(join(dir, 'tube.glb'), await new NodeIO().writeBinary(createBendingTube().document));
  await rejectsWith(farm(['submit', join(dir, 'tube.glb'), '--frames', '0', '--out', join(dir, 'f-#.png'), '--allow-origin', 'https://cdn.example.com', '--redis', closed]), 'INVALID_OPTION', '--allow-origin', /workers fetch only from their own/);
});

function refusedAt(data: unknown, field: string, message?: RegExp): void {
  assert.throws(() => validateFrameData(data), (e: unknown) => {
    assert.ok(e instanceof GpuRendererError, String(e));
    assert.equal(e.code, 'FARM_JOB_REFUSED', e.message);
    assert.equal(e.field, field, e.message);
    if (message) assert.match(e.message, message);
    return true;
  });
}

test('job data schema: sizes, unknown keys, non-finite and out-of-range numbers, origins and sequences are refused, naming the field', () => {
  type Loose = Record<string, unknown> & { render: Record<string, unknown>; item: Record<string, unknown> };
  const good = JSON.parse(JSON.stringify(frameData('job-1', '/farm/assets/tube.glb', '/farm/frames/f-0000.png'))) as Loose;
  assert.equal(validateFrameData(good), good);
  const edit = (change: (d: typeof good) => void): unknown => {
    const copy = structuredClone(good);
    change(copy);
    return copy;
  };
  refusedAt('text', '/', /expected an object/);
  refusedAt(edit((d) => void (d.render.camera = 'x'.repeat(frameDataLimits.jsonChars))), '/', /over the limit of 65536/);
  refusedAt(edit((d) => void (d.render.camera = 'x'.repeat(frameDataLimits.nameChars + 1))), 'render.camera', /longer than 256/);
  refusedAt(edit((d) => void (d.path = `/${'a'.repeat(frameDataLimits.pathChars)}`)), 'path', /longer than 4096/);
  refusedAt(edit((d) => void (d.render.colour = 'red')), 'render.colour', /unknown key/);
  refusedAt(edit((d) => void (d.extra = 1)), 'extra', /unknown key/);
  refusedAt(JSON.parse(JSON.stringify(good).replace('{', '{"__proto__":{"polluted":true},')), '__proto__', /unknown key/);
  refusedAt(edit((d) => void (d.render.exposure = Number.POSITIVE_INFINITY)), 'render.exposure', /finite/);
  refusedAt(edit((d) => void (d.item.time = Number.NaN)), 'item.time', /finite/);
  refusedAt(edit((d) => void (d.render.width = 1e9)), 'render.width', /1\.\.16384/);
  refusedAt(edit((d) => void (d.render.spp = 1.5)), 'render.spp', /integer/);
  refusedAt(edit((d) => void (d.render.cameraPosition = [0, 0, 1e30])), 'render.cameraPosition[2]', /1000000000000000000/);
  refusedAt(edit((d) => void (d.render.aovs = ['albedo', 'passwords'])), 'render.aovs[1]', /one of/);
  refusedAt(edit((d) => void (d.render.out = 'relative/f-####.png')), 'render.out', /absolute path/);
  refusedAt(edit((d) => void (d.render.scenePath = 'https://evil.example/tube.glb')), 'render.scenePath', /absolute path/);
  refusedAt(edit((d) => void (d.path = '/farm/frames/f\n.png')), 'path', /control characters/);
  refusedAt(edit((d) => void (d.render.allowedOrigins = ['https://evil.example'])), 'render.allowedOrigins', /worker's own setting/);
  refusedAt(edit((d) => void (d.render.frames = [0, 1])), 'render.frames', /planned at submission/);
  refusedAt(edit((d) => void (d.job = 'a/b')), 'job', /does not match/);
  refusedAt(edit((d) => void delete d.render.width), 'render.width', /missing/);
  refusedAt(edit((d) => void (d.item.turntableCamera = { position: [0, 0, 1], target: [0, 0, 0], up: [0, 1] })), 'item.turntableCamera.up', /3 items/);
  assert.ok(validateFrameData(edit((d) => void (d.render.env = 'none'))));
});

test('path map: the longest FROM wins, whole segments only; roots, map and origins from the environment', async (t) => {
  const map = [parsePathMapping('/mnt/studio=/srv/a', '--path-map'), parsePathMapping('/mnt/studio/frames=/srv/frames', '--path-map')];
  assert.equal(mapJobPath('/mnt/studio/frames/shot/f-0001.png', map), '/srv/frames/shot/f-0001.png');
  assert.equal(mapJobPath('/mnt/studio/assets/tube.glb', map), '/srv/a/assets/tube.glb');
  assert.equal(mapJobPath('/mnt/studio', map), '/srv/a');
  assert.equal(mapJobPath('/mnt/studio2/tube.glb', map), '/mnt/studio2/tube.glb', 'a prefix of a segment is no match');
  assert.equal(mapJobPath('/mnt/studio/../etc/passwd', map), '/mnt/etc/passwd', '.. is resolved before mapping');
  assert.throws(() => parsePathMapping('relative=/srv', '--path-map'), (e: unknown) => e instanceof GpuRendererError && e.field === '--path-map');
  assert.throws(() => parsePathMapping('/no-target', '--path-map'), (e: unknown) => e instanceof GpuRendererError && /FROM=TO/.test(e.message));
  assert.deepEqual((parseCliArgs(['farm', 'worker', '--path-map', '/a=/b', '--path-map', '/c=/d', '--output-root', 'x', '--asset-root', 'y', '--asset-root', 'z', '--allow-origin', 'https://cdn.example.com']) as FarmCommand & { action: 'worker' }).pathMap, [{ from: '/a', to: '/b' }, { from: '/c', to: '/d' }]);

  const dir = await mkdtemp(join(tmpdir(), 'gpu-renderer-farm-trust-'));
  t.after(() => rm(dir, { recursive: true, force: true }));
  await mkdir(join(dir, 'a'));
  await mkdir(join(dir, 'b'));
  await symlink(join(dir, 'b'), join(dir, 'b-link'));
  const trust = await resolveFarmTrust({}, {
    GPU_RENDERER_FARM_OUTPUT_ROOTS: [join(dir, 'a'), join(dir, 'b-link')].join(delimiter),
    GPU_RENDERER_FARM_ASSET_ROOTS: join(dir, 'a'),
    GPU_RENDERER_FARM_PATH_MAP: '/mnt/x=/srv/x; /mnt/y=/srv/y',
    GPU_RENDERER_FARM_ALLOW_ORIGINS: 'https://cdn.example.com, http://127.0.0.1:8080',
  });
  assert.deepEqual(trust.outputRoots, [join(dir, 'a'), join(dir, 'b')], 'roots are real paths');
  assert.deepEqual(trust.pathMap, [{ from: '/mnt/x', to: '/srv/x' }, { from: '/mnt/y', to: '/srv/y' }]);
  assert.deepEqual(trust.allowedOrigins, ['https://cdn.example.com', 'http://127.0.0.1:8080']);
  // Options win over the environment.
  assert.deepEqual((await resolveFarmTrust({ outputRoots: [join(dir, 'b')], assetRoots: [join(dir, 'b')] }, { GPU_RENDERER_FARM_OUTPUT_ROOTS: join(dir, 'a') })).outputRoots, [join(dir, 'b')]);
  await assert.rejects(resolveFarmTrust({ outputRoots: [dir], assetRoots: [dir] }, { GPU_RENDERER_FARM_ALLOW_ORIGINS: 'https://cdn.example.com/path' }), (e: unknown) => e instanceof GpuRendererError && e.field === 'GPU_RENDERER_FARM_ALLOW_ORIGINS');
});
