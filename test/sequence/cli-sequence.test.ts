// `gpu-renderer render model.glb --frames ... --out f-####.png`: every frame's pose follows the
// animation (its silhouette is the raster renderer's pose at frame / fps); a sequence killed midway
// leaves only whole frames and resumes without redoing them; --turntable orbits and --variants and
// --cameras render one image each, every frame compared with the raster renderer's view.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawn } from 'node:child_process';
import { mkdtemp, readdir, readFile, rm, stat, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { NodeIO } from '@gltf-transform/core';
import { ALL_EXTENSIONS } from '@gltf-transform/extensions';
import { decode } from 'fast-png';
import { parseCliArgs, type RenderCommand } from '../../src/cli/args.ts';
import { runSequenceCommand } from '../../src/cli/sequence-command.ts';
import { loadGltfScene } from '../../src/io/gltf/load-gltf-scene.ts';
import { planGltfSequence } from '../../src/sequence/gltf-sequence.ts';
import { testDevice } from '../helpers/gpu.ts';
import { createBendingTube } from './fixtures.ts';
import { coverage, createRasterPoser, iou, redMask } from './raster-pose.ts';

const root = fileURLToPath(new URL('../..', import.meta.url));
const cli = join(root, 'src/cli/main.ts');
const SIZE = 48;
const RENDER = ['--width', String(SIZE), '--height', String(SIZE), '--spp', '8', '--max-depth', '1', '--tone-mapping', 'linear'];

async function writeAsset(dir: string, variants = false): Promise<string> {
  const path = join(dir, 'tube.glb');
  await writeFile(path, await new NodeIO().registerExtensions(ALL_EXTENSIONS).writeBinary(createBendingTube({ variants }).document));
  return path;
}

function quiet(): { write(text: string): boolean; text: string } {
  return { text: '', write(text: string) { this.text += text; return true; } };
}

async function pngMask(path: string): Promise<Uint8Array> {
  const png = decode(await readFile(path));
  assert.equal(png.width, SIZE);
  return redMask(Uint8Array.from({ length: SIZE * SIZE * 4 }, (_, i) => png.data[Math.floor(i / 4) * png.channels + (i % 4)]!));
}

async function pngFiles(dir: string, prefix: string): Promise<string[]> {
  return (await readdir(dir)).filter((f) => f.startsWith(prefix) && f.endsWith('.png')).sort();
}

test('--frames 0-23 --fps 24 writes 24 frames posed at frame / fps; killed midway, it resumes without redoing frames', async (t) => {
  const dir = await mkdtemp(join(tmpdir(), 'gpu-renderer-seq-'));
  t.after(() => rm(dir, { recursive: true, force: true }));
  const asset = await writeAsset(dir);
  const args = ['render', asset, '--frames', '0-23', '--fps', '24', '--camera', 'Front', '--out', join(dir, 'f-####.png'), ...RENDER];
  // The real executable, killed once a few frames are on disk.
  // GPU_RENDERER_CLI_STDERR_COLUMNS marks the CLI's rendering process: it renders in the process
  // spawned here (no second one behind it), so SIGKILL stops the renderer itself.
  const child = spawn(process.execPath, [cli, ...args], { stdio: ['ignore', 'ignore', 'pipe'], env: { ...process.env, GPU_RENDERER_CLI_STDERR_COLUMNS: '' } });
  let stderr = '';
  child.stderr.setEncoding('utf8').on('data', (d: string) => (stderr += d));
  const exited = new Promise<void>((resolve) => child.on('close', () => resolve()));
  for (;;) {
    if ((await pngFiles(dir, 'f-')).length >= 4) break;
    if (child.exitCode !== null) assert.fail(`the CLI exited early: ${stderr}`);
    await new Promise((r) => setTimeout(r, 100));
  }
  child.kill('SIGKILL');
  await exited;
  const first = await pngFiles(dir, 'f-');
  assert.ok(first.length >= 4 && first.length < 24, `${first.length} frames before the kill`);
  const mtimes = new Map<string, number>();
  for (const f of first) {
    await pngMask(join(dir, f)); // whole files only: each decodes
    mtimes.set(f, (await stat(join(dir, f))).mtimeMs);
  }

  const io = quiet();
  const summary = await runSequenceCommand(parseCliArgs(args) as RenderCommand, { stderr: io, device: await testDevice() });
  assert.equal(summary.frames, 24);
  assert.equal(summary.skipped, first.length, io.text);
  assert.equal(summary.written, 24 - first.length);
  assert.equal(summary.renderers, 1, 'one path tracer, updated in place');
  const all = await pngFiles(dir, 'f-');
  assert.deepEqual(all, Array.from({ length: 24 }, (_, f) => `f-${String(f).padStart(4, '0')}.png`));
  assert.deepEqual(summary.files.map((f) => f.slice(dir.length + 1)), all.filter((f) => !mtimes.has(f)));
  for (const [f, mtime] of mtimes) assert.equal((await stat(join(dir, f))).mtimeMs, mtime, `${f} was not rendered again`);
  assert.deepEqual((await readdir(dir)).filter((f) => f.endsWith('.partial') && !mtimes.has(f)), [], 'the resumed run leaves no temporary files');

  const { document } = createBendingTube();
  const scene = await loadGltfScene(document, { camera: 'Front' });
  const raster = await createRasterPoser(await testDevice(), document, scene.materials, SIZE, SIZE);
  t.after(() => raster.destroy());
  const masks: Uint8Array[] = [];
  for (let f = 0; f < 24; f++) {
    const mask = await pngMask(join(dir, all[f]!));
    const reference = await raster.maskAt('Bend', f / 24, scene.camera);
    assert.ok(iou(mask, reference) > 0.9, `frame ${f}: IoU ${iou(mask, reference).toFixed(3)} against the raster pose at ${(f / 24).toFixed(3)} s (${coverage(mask)} vs ${coverage(reference)} px)`);
    masks.push(mask);
  }
  assert.ok(iou(masks[0]!, masks[23]!) < 0.75, `frame 0 and frame 23 show different poses (IoU ${iou(masks[0]!, masks[23]!).toFixed(3)})`);
});

test('--turntable orbits the framed model; --variants and --cameras render one image each', async (t) => {
  const dir = await mkdtemp(join(tmpdir(), 'gpu-renderer-seq-'));
  t.after(() => rm(dir, { recursive: true, force: true }));
  const asset = await writeAsset(dir, true);
  const device = await testDevice();
  const { document } = createBendingTube({ variants: true });
  const scene = await loadGltfScene(document, { camera: 'Front', time: 0.5 });
  const raster = await createRasterPoser(device, document, scene.materials, SIZE, SIZE);
  t.after(() => raster.destroy());

  // A turntable of the model bent at 0.5 s, in both variants.
  const run = (extra: string[]): Promise<unknown> => runSequenceCommand(parseCliArgs(['render', asset, ...extra, ...RENDER]) as RenderCommand, { stderr: quiet(), device });
  await run(['--turntable', '4', '--at', '0.5', '--variants', 'all', '--out', join(dir, 't-{variant}-#.png')]);
  assert.deepEqual(await pngFiles(dir, 't-'), ['t-Blue-0.png', 't-Blue-1.png', 't-Blue-2.png', 't-Blue-3.png', 't-Red-0.png', 't-Red-1.png', 't-Red-2.png', 't-Red-3.png']);
  const plan = planGltfSequence(scene, { turntable: 4 });
  const masks: Uint8Array[] = [];
  for (let k = 0; k < 4; k++) {
    const reference = await raster.maskAt('Bend', 0.5, plan[k]!.turntableCamera!);
    for (const variant of ['Red', 'Blue']) {
      const png = decode(await readFile(join(dir, `t-${variant}-${k}.png`)));
      const lit = (c: number): Uint8Array => Uint8Array.from({ length: SIZE * SIZE }, (_, i) => (png.data[i * png.channels + c]! > 127 ? 1 : 0));
      const mask = lit(variant === 'Red' ? 0 : 2);
      assert.equal(coverage(lit(variant === 'Red' ? 2 : 0)), 0, `${variant} frame ${k} shows only its variant's colour`);
      assert.ok(iou(mask, reference) > 0.9, `${variant} turntable frame ${k}: IoU ${iou(mask, reference).toFixed(3)}`);
      if (variant === 'Red') masks.push(mask);
    }
  }
  assert.ok(iou(masks[0]!, masks[1]!) < 0.8, `a quarter turn changes the view (IoU ${iou(masks[0]!, masks[1]!).toFixed(3)})`);

  await run(['--cameras', 'all', '--at', '0.5', '--variant', 'Red', '--out', join(dir, 'c-{camera}.png')]);
  assert.deepEqual(await pngFiles(dir, 'c-'), ['c-FrontCamera.png', 'c-SideCamera.png']);
  for (const camera of scene.cameras) {
    const reference = await raster.maskAt('Bend', 0.5, camera.camera);
    const mask = await pngMask(join(dir, `c-${camera.name}.png`));
    assert.ok(iou(mask, reference) > 0.9, `camera ${camera.name}: IoU ${iou(mask, reference).toFixed(3)}`);
  }
});
