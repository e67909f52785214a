// End-to-end: spawns the CLI as a user would (node src/cli/main.ts ...).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawn } from 'node:child_process';
import { mkdtemp, readFile, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { decode } from 'fast-png';

const root = fileURLToPath(new URL('../..', import.meta.url));
const cli = join(root, 'src/cli/main.ts');

function run(args: string[], cwd = root): Promise<{ code: number | null; stdout: string; stderr: string }> {
  return new Promise((resolve, reject) => {
    const child = spawn(process.execPath, [cli, ...args], { cwd, stdio: ['ignore', 'pipe', 'pipe'] });
    let stdout = '';
    let stderr = '';
    child.stdout.setEncoding('utf8').on('data', (d: string) => (stdout += d));
    child.stderr.setEncoding('utf8').on('data', (d: string) => (stderr += d));
    child.on('error', reject);
    child.on('close', (code) => resolve({ code, stdout, stderr }));
  });
}

test('--help prints usage and exits 0', async () => {
  const r = await run(['--help']);
  assert.equal(r.code, 0, r.stderr);
  assert.match(r.stdout, /Usage: gpu-renderer render \[scene\.json \| model\.glb \| model\.gltf\]/);
});

test('a bad flag exits 1 with "error [CODE] field: message"', async () => {
  const r = await run(['render', '--width', 'wide']);
  assert.equal(r.code, 1);
  assert.equal(r.stderr, 'error [INVALID_OPTION] --width: expected an integer, got "wide"\n');
});

test('an invalid scene file exits 1 naming the field', async () => {
  const dir = await mkdtemp(join(tmpdir(), 'gpu-renderer-cli-'));
  try {
    const scene = join(dir, 'scene.json');
    await writeFile(scene, JSON.stringify({ meshes: [{ positions: [0, 0, 'x'] }] }));
    const r = await run(['render', scene, '--out', join(dir, 'x.png')]);
    assert.equal(r.code, 1);
    assert.match(r.stderr, /^error \[INVALID_SCENE_FILE\] meshes\[0\]\.positions\[2\]: expected a finite number/);
  } finally {
    await rm(dir, { recursive: true, force: true });
  }
});

test('renders the Cornell box to a PNG with progress and a summary', async () => {
  const dir = await mkdtemp(join(tmpdir(), 'gpu-renderer-cli-'));
  try {
    const out = join(dir, 'cornell.png');
    const r = await run(['render', '--width', '32', '--height', '24', '--spp', '4', '--spp-per-frame', '2', '--max-depth', '4', '--out', out]);
    assert.equal(r.code, 0, r.stderr);
    // stderr is a pipe here, so progress comes as plain lines.
    assert.match(r.stderr, /render: 2\/4 spp +50%/);
    assert.match(r.stderr, /render: 4\/4 spp 100%/);
    assert.match(r.stderr, /wrote .*cornell\.png \(32x24, 4 spp\)/);
    assert.match(r.stderr, /samples\/s, .*rays\/s/);
    assert.match(r.stderr, /first frame \(2 spp, with shader compilation\) [0-9.]+s, before the clock/);
    assert.match(r.stderr, /adapter: \S+/);
    // Only what the CLI says: Dawn's adapter-limit notices (printed by native code on most Vulkan
    // drivers, llvmpipe included) are filtered out.
    assert.doesNotMatch(r.stderr, /artificially reduced/);
    for (const line of r.stderr.trim().split('\n')) assert.match(line, /^(render: |wrote | {2})/, `unexpected stderr line ${JSON.stringify(line)}`);
    const png = decode(await readFile(out));
    assert.deepEqual([png.width, png.height, png.channels, png.depth], [32, 24, 4, 8]);
    let lit = 0;
    // [left half, right half] counts.
    const red = [0, 0];
    const green = [0, 0];
    for (let i = 0; i < png.data.length; i += 4) {
      if (png.data[i] + png.data[i + 1] + png.data[i + 2] > 0) lit++;
      // Red wall on the left, green wall on the right, as seen from the open side.
      const side = (i / 4) % 32 < 16 ? 0 : 1;
      if (png.data[i] > png.data[i + 1] + 40) red[side]++;
      if (png.data[i + 1] > png.data[i] + 10) green[side]++;
      assert.equal(png.data[i + 3], 255);
    }
    // Most of the frame is the lit box; its red (left) and green (right) walls show even at 4 spp
    // (a few noisy pixels may land on the wrong side).
    assert.ok(lit > (32 * 24) / 2, `only ${lit} non-black pixels`);
    assert.ok(red[0] > 10 && red[0] > 4 * red[1], `red pixels left/right ${red}`);
    assert.ok(green[1] > 10 && green[1] > 4 * green[0], `green pixels left/right ${green}`);
  } finally {
    await rm(dir, { recursive: true, force: true });
  }
});

test('--time limits the sampling after the first frame, which compiles the shaders outside the clock', async () => {
  const dir = await mkdtemp(join(tmpdir(), 'gpu-renderer-cli-'));
  try {
    const out = join(dir, 'timed.png');
    const r = await run(['render', '--width', '16', '--height', '16', '--spp', '100000', '--spp-per-frame', '1', '--time', '400ms', '--max-depth', '2', '--out', out]);
    assert.equal(r.code, 0, r.stderr);
    assert.match(r.stderr, /stopped by the time limit/);
    const rendering = Number(/([0-9.]+)s rendering/.exec(r.stderr)?.[1]);
    const spp = Number(/\(16x16, (\d+) spp/.exec(r.stderr)?.[1]);
    // Sampling ran for the budget (a last frame may overrun it slightly), after the first frame's sample.
    assert.ok(rendering >= 0.35 && rendering < 2, `rendering ${rendering}s for --time 400ms`);
    assert.ok(spp > 1, `${spp} spp`);
  } finally {
    await rm(dir, { recursive: true, force: true });
  }
});
