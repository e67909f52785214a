// Sequence planning without a GPU: frame lists, output patterns, turntable cameras (checked against
// their geometric definition), glTF sequence plans, and the CLI's sequence and farm arguments.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { parseCliArgs, type RenderCommand } from '../../src/cli/args.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { parseJobFile } from '../../src/farm/farm-job.ts';
import { resolveFarmConnection } from '../../src/farm/connection.ts';
import { loadGltfScene } from '../../src/io/gltf/load-gltf-scene.ts';
import { parseFrameList } from '../../src/sequence/frame-list.ts';
import { expandOutputPattern, outputPaths } from '../../src/sequence/output-pattern.ts';
import { planGltfSequence, sequencePatternValues } from '../../src/sequence/gltf-sequence.ts';
import { turntableCamera } from '../../src/sequence/turntable.ts';
import { createBendingTube } from './fixtures.ts';

function throwsField(fn: () => unknown, field: string, message?: RegExp): void {
  assert.throws(fn, (e: unknown) => {
    assert.ok(e instanceof GpuRendererError, String(e));
    assert.equal(e.field, field, e.message);
    if (message) assert.match(e.message, message);
    return true;
  });
}

test('frame lists: ranges, steps and lists in the order given; bad items are errors quoting them', () => {
  assert.deepEqual(parseFrameList('0-3'), [0, 1, 2, 3]);
  assert.deepEqual(parseFrameList('0-10:5'), [0, 5, 10]);
  assert.deepEqual(parseFrameList('1-9:4'), [1, 5, 9]);
  assert.deepEqual(parseFrameList('7, 2,20-22'), [7, 2, 20, 21, 22]);
  throwsField(() => parseFrameList('5-2', '--frames'), '--frames', /"5-2" ends before it starts/);
  throwsField(() => parseFrameList('0-4:0'), 'frames', /step 0/);
  throwsField(() => parseFrameList('1,2,1'), 'frames', /frame 1 is listed twice/);
  throwsField(() => parseFrameList('a-b'), 'frames', /"a-b"/);
  throwsField(() => parseFrameList('-3'), 'frames');
  throwsField(() => parseFrameList(''), 'frames');
  throwsField(() => parseFrameList('0-1000000000'), 'frames', /more than/);
});

test('output patterns: #### pads the frame, {variant} and {camera} become file-safe names, collisions are errors', () => {
  assert.equal(expandOutputPattern('out/f-####.png', { frame: 7 }), 'out/f-0007.png');
  assert.equal(expandOutputPattern('f-##.exr', { frame: 1234 }), 'f-1234.exr');
  assert.equal(expandOutputPattern('{variant}/{camera}-#.png', { frame: 3, variant: 'Midnight Blue/2', camera: 'Cam.1' }), 'Midnight_Blue_2/Cam.1-3.png');
  throwsField(() => outputPaths('f.png', [{ frame: 0 }, { frame: 1 }], '--out'), '--out', /####/);
  throwsField(() => outputPaths('f-#.png', [{ frame: 0, variant: 'a' }, { frame: 0, variant: 'b' }], '--out'), '--out', /\{variant\}/);
  throwsField(() => outputPaths('{variant}-#.png', [{ frame: 1, variant: 'a b' }, { frame: 1, variant: 'a_b' }], '--out'), '--out', /both be written to a_b-1.png/);
});

test('turntable cameras: one distance, the given elevation, equal azimuth steps from +Z, the bounding sphere inside the view', () => {
  const bounds = { min: [1, 0, -2] as [number, number, number], max: [3, 4, 0] as [number, number, number] };
  const center = [2, 2, -1];
  const radius = Math.hypot(2, 4, 2) / 2;
  for (const aspect of [1, 0.5, 2]) {
    const cameras = [0, 1, 2, 3, 4, 5].map((k) => turntableCamera(bounds, k, { frames: 6, elevationDegrees: 30, fovYDegrees: 40 }, aspect));
    const distances = cameras.map((c) => Math.hypot(...c.position!.map((p, a) => p - center[a]!)));
    for (const [k, c] of cameras.entries()) {
      assert.deepEqual(c.target, center);
      const d = c.position!.map((p, a) => p - center[a]!);
      assert.ok(Math.abs(distances[k]! - distances[0]!) < 1e-9);
      assert.ok(Math.abs(Math.asin(d[1]! / distances[k]!) - Math.PI / 6) < 1e-9, 'elevation 30 degrees');
      const off = Math.atan2(d[0]!, d[2]!) - (k * Math.PI) / 3;
      assert.ok(Math.abs(Math.atan2(Math.sin(off), Math.cos(off))) < 1e-9, `azimuth of frame ${k}: 60 k degrees from +Z`);
      // The sphere's angular radius fits half of the narrower field of view (less the default 5 % margin).
      const halfY = (20 * Math.PI) / 180;
      const halfX = Math.atan(Math.tan(halfY) * aspect);
      assert.ok(Math.asin(radius / distances[k]!) <= Math.min(halfX, halfY) + 1e-12);
      assert.ok(Math.asin((1.1 * radius) / distances[k]!) > Math.min(halfX, halfY), 'and nearly fills it');
    }
  }
});

test('glTF sequence plans: frames at frame / fps, variant by variant, cameras by name, typed errors', async () => {
  const scene = await loadGltfScene(createBendingTube({ variants: true }).document);
  const plan = planGltfSequence(scene, { frames: [0, 12, 24], fps: 24, variants: 'all' });
  assert.deepEqual(plan.map((i) => [i.index, i.frame, i.time, i.variant]), [[0, 0, 0, 'Red'], [1, 12, 0.5, 'Red'], [2, 24, 1, 'Red'], [3, 0, 0, 'Blue'], [4, 12, 0.5, 'Blue'], [5, 24, 1, 'Blue']]);
  const turntable = planGltfSequence(scene, { turntable: 3, time: 0.25 });
  assert.deepEqual(turntable.map((i) => [i.frame, i.time, i.turntableCamera !== undefined]), [[0, 0.25, true], [1, 0.25, true], [2, 0.25, true]]);
  const cameras = planGltfSequence(scene, { cameras: ['Side', 0] });
  assert.deepEqual(cameras.map((i) => [i.cameraIndex, i.cameraName]), [[1, 'SideCamera'], [0, 'FrontCamera']]);
  assert.deepEqual(outputPaths('{camera}.png', sequencePatternValues(cameras)), ['SideCamera.png', 'FrontCamera.png']);
  throwsField(() => planGltfSequence(scene, { variants: ['Red', 'Green'] }), 'variants[1]', /"Green"/);
  throwsField(() => planGltfSequence(scene, { cameras: ['Top'] }), 'cameras[0]', /"Top"/);
  throwsField(() => planGltfSequence(scene, { frames: [0], fps: 0 }), 'fps');
  throwsField(() => planGltfSequence(scene, { frames: [0, -1] }), 'frames[1]');
  throwsField(() => planGltfSequence(scene, { frames: [0], time: 1 }), 'time');
  throwsField(() => planGltfSequence(scene, { turntable: 0 }), 'turntable.frames');
  throwsField(() => planGltfSequence(scene, { turntable: 4, cameras: 'all' }), 'cameras');
  const plain = await loadGltfScene(createBendingTube().document);
  throwsField(() => planGltfSequence(plain, { variants: 'all' }), 'variants', /no KHR_materials_variants/);
});

test('CLI: sequence flags parse, and their misuse is an error naming the flag', () => {
  const c = parseCliArgs(['render', 'a.glb', '--frames', '0-23:2', '--fps', '12', '--animation', 'Walk', '--out', 'f-####.exr', '--overwrite']) as RenderCommand;
  assert.deepEqual([c.frames?.length, c.fps, c.animation, c.format, c.overwrite], [12, 12, 'Walk', 'exr', true]);
  const v = parseCliArgs(['render', 'a.glb', '--variants', 'A,B', '--turntable', '8', '--out', '{variant}-##.png']) as RenderCommand;
  assert.deepEqual([v.variants, v.turntable], [['A', 'B'], 8]);
  throwsField(() => parseCliArgs(['render', 'a.glb', '--frames', '0-3', '--out', 'f.png']), '--out', /####/);
  throwsField(() => parseCliArgs(['render', 'a.glb', '--variants', 'all', '--out', 'f.png']), '--out', /\{variant\}/);
  throwsField(() => parseCliArgs(['render', 'a.glb', '--cameras', 'all', '--out', 'f.png']), '--out', /\{camera\}/);
  throwsField(() => parseCliArgs(['render', 'a.glb', '--frames', '0-3', '--at', '1', '--out', 'f-#.png']), '--at');
  throwsField(() => parseCliArgs(['render', 'a.glb', '--fps', '30']), '--fps');
  throwsField(() => parseCliArgs(['render', 'a.glb', '--overwrite']), '--overwrite');
  throwsField(() => parseCliArgs(['render', 'scene.json', '--frames', '0-3', '--out', 'f-#.png']), '--frames', /glTF/);
  throwsField(() => parseCliArgs(['render', 'a.glb', '--turntable', '4', '--cameras', 'all', '--out', '{camera}-#.png']), '--cameras');
  throwsField(() => parseCliArgs(['render', 'a.glb', '--at', '-1']), '--at');
  throwsField(() => parseCliArgs(['farm', 'launch']), 'command', /submit, worker or status/);
  throwsField(() => parseCliArgs(['farm', 'worker', '--lock-duration', 'soon']), '--lock-duration');
  throwsField(() => parseCliArgs(['farm', 'status', '--timeout', '5']), '--timeout', /--wait/);
});

test('farm: job files become render commands with paths against the file; Redis addresses are checked', () => {
  const command = parseJobFile(JSON.stringify({ scene: 'assets/fox.glb', out: 'frames/fox-{variant}-####.png', frames: [0, 2, 4], fps: 12, variants: 'all', envIntensity: 2, denoise: true, energyCompensation: false }), '/jobs/fox.json', '/jobs');
  assert.equal(command.scenePath, '/jobs/assets/fox.glb');
  assert.equal(command.out, '/jobs/frames/fox-{variant}-####.png');
  assert.deepEqual([command.frames, command.fps, command.variants, command.envIntensity, command.denoise, command.energyCompensation], [[0, 2, 4], 12, 'all', 2, true, false]);
  throwsField(() => parseJobFile('{"scene": 3}', 'j.json', '/'), '/scene');
  throwsField(() => parseJobFile('{"out": "f-#.png", "frames": "0-1"}', 'j.json', '/'), '/scene');
  throwsField(() => parseJobFile('[1]', 'j.json', '/'), '');
  throwsField(() => parseJobFile('{"scene": "a.glb", "frames": "0-1", "out": "f-#.png", "width": {"px": 3}}', 'j.json', '/'), '/width');
  assert.deepEqual(resolveFarmConnection({}, {}), { url: 'redis://127.0.0.1:6379', source: 'default', shown: 'redis://127.0.0.1:6379', queue: 'gpu-renderer' });
  assert.equal(resolveFarmConnection({ redis: 'rediss://farm:s3cret@r:1' }, {}).shown, 'rediss://farm:***@r:1', 'a password is never shown');
  assert.equal(resolveFarmConnection({}, { REDIS_URL: 'redis://cache:6380' }).url, 'redis://cache:6380');
  assert.equal(resolveFarmConnection({ redis: 'rediss://r:1', queue: 'films' }, { REDIS_URL: 'redis://x:1' }).source, '--redis');
  throwsField(() => resolveFarmConnection({ redis: 'not a url' }, {}), '--redis');
  throwsField(() => resolveFarmConnection({}, { REDIS_URL: 'http://x:1' }), 'REDIS_URL');
  throwsField(() => resolveFarmConnection({ queue: 'a:b' }, {}), '--queue');
});
