import { test } from 'node:test';
import assert from 'node:assert/strict';
import { parseCliArgs, parseRenderArgs, renderDefaults, usage, type RenderCommand } from '../../src/cli/args.ts';
import { rendererSettings } from '../../src/cli/render-command.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';

function rejects(argv: string[], field: string, message?: RegExp): void {
  assert.throws(
    () => parseCliArgs(argv),
    (e: unknown) => {
      assert.ok(e instanceof GpuRendererError, String(e));
      assert.equal(e.code, 'INVALID_OPTION');
      assert.equal(e.field, field);
      if (message) assert.match(e.message, message);
      return true;
    },
  );
}

function render(argv: string[]): RenderCommand {
  const command = parseRenderArgs(argv);
  assert.equal(command.kind, 'render');
  return command as RenderCommand;
}

test('defaults render the built-in scene', () => {
  assert.deepEqual(parseCliArgs(['render']), { kind: 'render', scenePath: undefined, ...renderDefaults, aovs: [] });
});

test('every flag, in both --flag value and --flag=value forms', () => {
  const argv = ['scene.json', '--width', '32', '--height=24', '--spp', '16', '--spp-per-frame=2', '--max-depth', '5', '--seed', '4294967295',
    '--tone-mapping', 'aces', '--exposure=0.5', '--out', 'out/x.png', '--no-energy-compensation'];
  assert.deepEqual(parseRenderArgs(argv), {
    kind: 'render', scenePath: 'scene.json', width: 32, height: 24, spp: 16, sppPerFrame: 2, maxDepth: 5, seed: 4294967295,
    toneMapping: 'aces', exposure: 0.5, exposureEv: 0, out: 'out/x.png', format: 'png', denoise: false, half: false, energyCompensation: false, negativeTexels: 'zero', aovs: [],
  });
  // The scene may come after the flags, or after `--` (a name starting with a dash).
  assert.equal(render(['--spp', '1', 'a.json']).scenePath, 'a.json');
  assert.equal(render(['--', '-odd.json']).scenePath, '-odd.json');
});

test('glTF scenes: --camera and --variant', () => {
  const command = render(['model.glb', '--camera', 'Camera.001', '--variant=Midnight']);
  assert.deepEqual([command.scenePath, command.camera, command.variant], ['model.glb', 'Camera.001', 'Midnight']);
  assert.equal(render(['Model.GLTF', '--camera', 'top']).camera, 'top');
  // Without the flags the command has no camera/variant keys at all.
  assert.deepEqual(Object.keys(render(['model.glb'])).filter((k) => k === 'camera' || k === 'variant'), []);
  rejects(['render', 'scene.json', '--camera', 'top'], '--camera', /glTF scenes/);
  rejects(['render', '--variant', 'x'], '--variant', /glTF scenes/);
  rejects(['render', 'a.glb', '--camera='], '--camera', /expects a name/);
  rejects(['render', 'a.glb', '--variant'], '--variant', /expects a value/);
});

test('--bvh-build chooses where the BVH is built', () => {
  assert.equal(render(['--bvh-build', 'gpu']).accelerationBuildMode, 'gpu');
  assert.equal(render(['--bvh-build=cpu-upload']).accelerationBuildMode, 'cpu-upload');
  assert.equal(render([]).accelerationBuildMode, undefined);
  rejects(['render', '--bvh-build', 'fpga'], '--bvh-build', /cpu-upload or gpu/);
});

test('--integrator chooses the path tracer form and reaches the renderer settings', () => {
  assert.equal(render(['--integrator', 'megakernel']).integrator, 'megakernel');
  assert.equal(rendererSettings(render(['--integrator=megakernel'])).integrator, 'megakernel');
  assert.equal(render([]).integrator, undefined);
  assert.equal('integrator' in rendererSettings(render([])), false);
  rejects(['render', '--integrator', 'persistent'], '--integrator', /wavefront or megakernel/);
});

test('samples per frame never exceeds the target unless given', () => {
  assert.equal(render(['--spp', '2']).sppPerFrame, 2);
  assert.equal(render(['--spp', '100']).sppPerFrame, renderDefaults.sppPerFrame);
});

test('help', () => {
  for (const argv of [[], ['--help'], ['-h'], ['help'], ['render', '--help'], ['render', '--width', '3', '-h']]) {
    const command = parseCliArgs(argv);
    assert.equal(command.kind, 'help', argv.join(' '));
    assert.equal(command.kind === 'help' && command.text, usage);
  }
  for (const flag of ['--width', '--height', '--spp', '--max-depth', '--seed', '--tone-mapping', '--exposure', '--out', '--camera', '--variant', '.glb', '.gltf']) assert.ok(usage.includes(flag), flag);
});

test('bad commands and flags are typed errors naming the flag', () => {
  rejects(['draw'], 'command', /unknown command "draw"/);
  rejects(['render', '--widht', '3'], '--widht', /unknown option/);
  rejects(['render', '--width'], '--width', /expects a value/);
  rejects(['render', '--width', '--height', '3'], '--width', /expects a value/);
  rejects(['render', '--width', '0'], '--width', /between 1 and 16384/);
  rejects(['render', '--width', '12.5'], '--width', /integer/);
  rejects(['render', '--height', 'abc'], '--height', /integer/);
  rejects(['render', '--spp', '-4'], '--spp');
  rejects(['render', '--max-depth', '33'], '--max-depth', /between 1 and 32/);
  rejects(['render', '--seed', '4294967296'], '--seed');
  rejects(['render', '--tone-mapping', 'filmic'], '--tone-mapping', /neutral, aces, agx or linear/);
  rejects(['render', '--exposure', '0'], '--exposure', /> 0/);
  rejects(['render', '--exposure', 'Infinity'], '--exposure');
  rejects(['render', '--exposure='], '--exposure');
  rejects(['render', '--out='], '--out');
  rejects(['render', 'a.json', 'b.json'], 'scene', /only one scene file/);
});

test('error messages carry the field prefix the CLI prints', () => {
  try {
    parseCliArgs(['render', '--spp', 'x']);
    assert.fail('expected an error');
  } catch (e) {
    assert.ok(e instanceof GpuRendererError);
    assert.equal(`error [${e.code}] ${e.message}`, 'error [INVALID_OPTION] --spp: expected an integer, got "x"');
  }
});

test('camera flags: --orbit, --camera-position / --camera-target, --fov, with typed errors', () => {
  assert.deepEqual(render(['m.glb', '--orbit', '30,-15']).orbit, { azimuthDegrees: 30, elevationDegrees: -15 });
  assert.deepEqual(render(['m.glb', '--orbit=-90,90,2.5']).orbit, { azimuthDegrees: -90, elevationDegrees: 90, distance: 2.5 });
  const placed = render(['s.json', '--camera-position', '1,2,3', '--camera-target=0,0.5,-1', '--fov', '30']);
  assert.deepEqual([placed.cameraPosition, placed.cameraTarget, placed.fovYDegrees], [[1, 2, 3], [0, 0.5, -1], 30]);
  assert.deepEqual(render(['--camera-position', '0,0,5']).cameraPosition, [0, 0, 5]);
  rejects(['render', '--orbit', '30'], '--orbit', /azimuth,elevation/);
  rejects(['render', '--orbit', '30,91'], '--orbit', /elevation must be within \[-90, 90\]/);
  rejects(['render', '--orbit', '30,10,0'], '--orbit', /distance must be > 0/);
  rejects(['render', '--orbit', '30,x'], '--orbit', /finite numbers/);
  rejects(['render', '--camera-position', '1,2'], '--camera-position', /x,y,z/);
  rejects(['render', '--camera-position', '1,2,NaN'], '--camera-position', /x,y,z/);
  rejects(['render', '--camera-target', '1,2,3'], '--camera-target', /needs --camera-position/);
  rejects(['render', '--orbit', '0,0', '--camera-position', '1,2,3'], '--orbit', /cannot be combined/);
  rejects(['render', 'm.glb', '--camera', 'top', '--orbit', '0,0'], '--camera', /--orbit places one instead/);
  rejects(['render', '--fov', '0'], '--fov', /\(0, 179\]/);
  rejects(['render', '--fov', '180'], '--fov', /\(0, 179\]/);
});

test('--negative-texels: zero (default) or error', () => {
  assert.equal(render([]).negativeTexels, 'zero');
  assert.equal(render(['--negative-texels', 'error']).negativeTexels, 'error');
  rejects(['render', '--negative-texels', 'clamp'], '--negative-texels', /zero or error/);
});
