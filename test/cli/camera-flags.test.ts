// The CLI's camera flags applied to a loaded scene (no GPU): --orbit around the scene bounds'
// centre (fitted to the image unless a distance is given), --camera-position with or without
// --camera-target, --fov on whichever camera is rendered from.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { parseRenderArgs, type RenderCommand } from '../../src/cli/args.ts';
import { applyCameraFlags } from '../../src/cli/camera-flags.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { frameBounds } from '../../src/scene/camera-framing.ts';
import type { WavefrontSceneDescription } from '../../src/scene/types.ts';

// A 4 x 2 x 0 quad centred on (1, 1, 0), and a scene camera that the flags replace.
const scene: WavefrontSceneDescription = {
  meshes: [{ positions: [-1, 0, 0, 3, 0, 0, 3, 2, 0, -1, 2, 0], indices: [0, 1, 2, 0, 2, 3] }],
  camera: { type: 'perspective', position: [0, 0, 10], target: [0, 0, 0], fovYDegrees: 60 },
};
const bounds = { min: [-1, 0, 0] as [number, number, number], max: [3, 2, 0] as [number, number, number] };
const command = (argv: string[]): RenderCommand => parseRenderArgs(['--width', '200', '--height', '100', ...argv]) as RenderCommand;

test('--orbit frames the bounds from the direction given, for the image aspect; a distance is kept', () => {
  assert.deepEqual(applyCameraFlags(scene, command(['--orbit', '-40,10'])).camera, frameBounds(bounds, { azimuthDegrees: -40, elevationDegrees: 10, aspectRatio: 2 }));
  const far = applyCameraFlags(scene, command(['--orbit', '0,0,12', '--fov', '20'])).camera!;
  assert.deepEqual(far, { type: 'perspective', position: [1, 1, 12], target: [1, 1, 0], up: [0, 1, 0], fovYDegrees: 20 });
});

test('--camera-position looks at --camera-target, else at the bounds centre; --fov alone changes the scene camera', () => {
  assert.deepEqual(applyCameraFlags(scene, command(['--camera-position', '5,5,5', '--camera-target', '0,1,0'])).camera, { type: 'perspective', position: [5, 5, 5], target: [0, 1, 0], up: [0, 1, 0], fovYDegrees: 45 });
  assert.deepEqual(applyCameraFlags(scene, command(['--camera-position', '1,9,0'])).camera!.target, [1, 1, 0]);
  assert.deepEqual(applyCameraFlags(scene, command(['--fov', '25'])).camera, { ...scene.camera, fovYDegrees: 25 });
  assert.equal(applyCameraFlags(scene, command([])), scene);
  const fails = (s: WavefrontSceneDescription, argv: string[], field: string): void => {
    assert.throws(() => applyCameraFlags(s, command(argv)), (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_OPTION' && e.field === field);
  };
  fails({ ...scene, camera: { type: 'orthographic', position: [0, 0, 1], target: [0, 0, 0] } }, ['--fov', '30'], '--fov');
  fails({}, ['--camera-position', '1,2,3'], '--camera-position');
  fails(scene, ['--camera-position', '1,1,0'], '--camera-target');
});
