// The CLI's output options: argument parsing (typed errors for bad input), an OpenEXR round trip
// with AOV layers (read back by an independent reader and compared with the same render through the
// API), half floats, Radiance .hdr, --denoise keeping the raw beauty, --time and --noise stopping.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawn } from 'node:child_process';
import { mkdtemp, readFile, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { parseRenderArgs, type RenderCommand } from '../../src/cli/args.ts';
import { cliMinimumSamples } from '../../src/cli/render-command.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import { createCornellBoxScene } from '../../src/scene/cornell-box.ts';
import { testDevice } from '../helpers/gpu.ts';
import { readHdrWithThree } from '../io/images/independent-readers.ts';
import { readExrChannels } from './exr-reader.ts';

const root = fileURLToPath(new URL('../..', import.meta.url));
const cli = join(root, 'src/cli/main.ts');

function run(args: string[]): Promise<{ code: number | null; stderr: string; seconds: number }> {
  const started = performance.now();
  return new Promise((resolve, reject) => {
    const child = spawn(process.execPath, [cli, 'render', ...args], { cwd: root, stdio: ['ignore', 'ignore', 'pipe'] });
    let stderr = '';
    child.stderr.setEncoding('utf8').on('data', (d: string) => (stderr += d));
    child.on('error', reject);
    child.on('close', (code) => resolve({ code, stderr, seconds: (performance.now() - started) / 1000 }));
  });
}

const parse = (args: string[]): RenderCommand => {
  const c = parseRenderArgs(args);
  assert.equal(c.kind, 'render');
  return c as RenderCommand;
};
const fails = (args: string[], field: string) => assert.throws(() => parseRenderArgs(args), (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_OPTION' && e.field === field, args.join(' '));

test('output flags parse, and bad values are typed errors naming the flag', () => {
  const c = parse(['--out', 'x.exr', '--aov', 'albedo,Normal,objectId', '--time', '1m30s', '--noise', '0.01', '--min-spp', '8', '--denoise', '--half', '--exposure-ev', '-1.5']);
  assert.deepEqual(
    { format: c.format, aovs: c.aovs, time: c.timeLimitMs, noise: c.noiseThreshold, min: c.minSpp, denoise: c.denoise, half: c.half, ev: c.exposureEv },
    { format: 'exr', aovs: ['albedo', 'normal', 'objectId'], time: 90_000, noise: 0.01, min: 8, denoise: true, half: true, ev: -1.5 },
  );
  assert.equal(parse(['--out', 'x.HDR']).format, 'hdr');
  assert.equal(parse([]).format, 'png');
  // Cycles' minimum for the threshold, at most spp / 4.
  assert.equal(cliMinimumSamples(parse(['--noise', '0.01', '--spp', '1024'])), 64);
  assert.equal(cliMinimumSamples(parse(['--noise', '0.01', '--spp', '64'])), 16);
  assert.equal(cliMinimumSamples(parse(['--noise', '0.01', '--spp', '4'])), 2);
  assert.equal(cliMinimumSamples(parse([])), undefined);
  fails(['--aov', 'albedo,beauty', '--out', 'x.exr'], '--aov');
  fails(['--aov', 'albedo'], '--aov');
  fails(['--aov', 'albedo', '--out', 'x.hdr'], '--aov');
  fails(['--half', '--out', 'x.png'], '--half');
  fails(['--out', 'x.tiff'], '--out');
  fails(['--time', '0s'], '--time');
  fails(['--time', 'soon'], '--time');
  fails(['--noise', '0'], '--noise');
  fails(['--noise', '-0.1'], '--noise');
  fails(['--min-spp', '8'], '--min-spp');
  fails(['--noise', '0.1', '--min-spp', '1'], '--min-spp');
  fails(['--noise', '0.1', '--spp', '4', '--min-spp', '8'], '--min-spp');
  fails(['--exposure-ev', 'bright'], '--exposure-ev');
  fails(['--denoise=yes'], '--denoise');
  // --denoise takes an optional denoiser; a following scene path is not one.
  assert.equal(parse(['--denoise', 'oidn']).denoise, 'oidn');
  assert.equal(parse(['--denoise=atrous']).denoise, 'atrous');
  const withScene = parse(['--denoise', 'scene.glb']);
  assert.equal(withScene.denoise, true);
  assert.equal(withScene.scenePath, 'scene.glb');
  fails(['--denoise=bilateral'], '--denoise');
});

test('an OpenEXR with AOV layers round-trips through the CLI: the same values as the API renders', async () => {
  const dir = await mkdtemp(join(tmpdir(), 'gpu-renderer-output-'));
  try {
    const out = join(dir, 'cornell.exr');
    const half = join(dir, 'half.exr');
    const args = ['--width', '16', '--height', '12', '--spp', '4', '--spp-per-frame', '2', '--max-depth', '4', '--seed', '3'];
    const aovs = ['albedo', 'normal', 'depth', 'emission', 'objectId', 'materialId', 'variance', 'sampleCount'] as const;
    const r = await run([...args, '--out', out, '--aov', aovs.join(',')]);
    assert.equal(r.code, 0, r.stderr);
    assert.match(r.stderr, /wrote .*cornell\.exr \(16x12, 4 spp\); AOVs albedo, normal, depth, emission, objectId, materialId, variance, sampleCount/);
    const rh = await run([...args, '--out', half, '--aov', 'albedo,objectId', '--half']);
    assert.equal(rh.code, 0, rh.stderr);

    const renderer = await createWavefrontPathTracingComputeRenderer({ device: await testDevice(), width: 16, height: 12, maxDepth: 4, seed: 3, samplesPerPixel: 2, aovs: true, ...createCornellBoxScene() });
    try {
      await renderer.renderFrame();
      await renderer.renderFrame();
      const file = readExrChannels(new Uint8Array(await readFile(out)));
      assert.equal(file.width, 16);
      assert.equal(file.height, 12);
      const radiance = (await renderer.readRadiance()).data;
      ['R', 'G', 'B', 'A'].forEach((c, k) => {
        assert.equal(file.channels[c]!.type, 'float');
        file.channels[c]!.values.forEach((v, p) => assert.equal(v, radiance[4 * p + k], `${c} at ${p}`));
      });
      const channelNames = { albedo: ['R', 'G', 'B'], normal: ['X', 'Y', 'Z'], depth: ['Z'], emission: ['R', 'G', 'B'], objectId: ['id'], materialId: ['id'], variance: ['R', 'G', 'B'], sampleCount: ['count'] };
      for (const name of aovs) {
        const image = (await renderer.readAov(name)).data;
        channelNames[name].forEach((c, k) => {
          const channel = file.channels[`${name}.${c}`];
          assert.ok(channel, `channel ${name}.${c}`);
          channel.values.forEach((v, p) => assert.ok(Object.is(v, image[4 * p + k]) || v === image[4 * p + k], `${name}.${c} at ${p}: ${v} vs ${image[4 * p + k]}`));
        });
      }
      assert.deepEqual(Object.keys(file.channels).sort(), ['A', 'B', 'G', 'R', ...aovs.flatMap((n) => channelNames[n].map((c) => `${n}.${c}`))].sort());
      // Half floats: the beauty and albedo rounded to binary16; ids stay float (exact).
      const h = readExrChannels(new Uint8Array(await readFile(half)));
      assert.equal(h.channels.R!.type, 'half');
      assert.equal(h.channels['objectId.id']!.type, 'float');
      h.channels.G!.values.forEach((v, p) => assert.equal(v, Math.f16round(radiance[4 * p + 1]!)));
      const ids = (await renderer.readAov('objectId')).data;
      h.channels['objectId.id']!.values.forEach((v, p) => assert.equal(v, ids[4 * p]));
    } finally {
      renderer.destroy();
    }
  } finally {
    await rm(dir, { recursive: true, force: true });
  }
});

test('.hdr output, --denoise keeping the raw beauty as a layer, --time and --noise stopping the render', async () => {
  const dir = await mkdtemp(join(tmpdir(), 'gpu-renderer-output-'));
  try {
    const hdr = join(dir, 'sky.hdr');
    const sky = join(dir, 'sky.json');
    // Only a uniform sky: every sample of every pixel is the same, so every pixel converges at the minimum.
    await writeFile(sky, JSON.stringify({
      camera: { type: 'orthographic', position: [0, 0, 2], target: [0, 0, 0], up: [0, 1, 0], orthographicHeight: 2 },
      environment: { color: [0.25, 0.5, 1] },
    }));
    const a = await run([sky, '--width', '8', '--height', '8', '--spp', '64', '--noise', '0.01', '--min-spp', '4', '--out', hdr]);
    assert.equal(a.code, 0, a.stderr);
    assert.match(a.stderr, /wrote .*sky\.hdr \(8x8, 4 spp\); stopped by the noise target/);
    const image = readHdrWithThree(new Uint8Array(await readFile(hdr)));
    [0.25, 0.5, 1].forEach((v, c) => assert.ok(Math.abs(image.data[c]! - v) <= v / 128, `channel ${c}: ${image.data[c]}`));

    const exr = join(dir, 'denoised.exr');
    const b = await run(['--width', '16', '--height', '16', '--spp', '4', '--max-depth', '3', '--denoise', 'atrous', '--out', exr]);
    assert.equal(b.code, 0, b.stderr);
    assert.match(b.stderr, /denoised \(a-trous\)/);
    const file = readExrChannels(new Uint8Array(await readFile(exr)));
    let differs = 0;
    file.channels.G!.values.forEach((v, p) => (differs += Math.abs(v - file.channels['raw.G']!.values[p]!) > 1e-4 ? 1 : 0));
    assert.ok(differs > 64, 'the beauty is denoised, the raw layer is not');

    const c = await run(['--width', '32', '--height', '32', '--spp', '1000000', '--time', '1.5s', '--out', join(dir, 'timed.png')]);
    assert.equal(c.code, 0, c.stderr);
    assert.match(c.stderr, /stopped by the time limit/);
    const rendering = Number(/, ([\d.]+)s rendering/.exec(c.stderr)?.[1]);
    assert.ok(rendering >= 1.4 && rendering < 4, `${rendering} s rendering for a 1.5 s limit`);
  } finally {
    await rm(dir, { recursive: true, force: true });
  }
});

test('bad output flags exit 1 with the typed error', async () => {
  const r = await run(['--aov', 'albedo,shadow', '--out', 'x.exr']);
  assert.equal(r.code, 1);
  assert.match(r.stderr, /^error \[INVALID_OPTION\] --aov: unknown AOV "shadow"/);
});
