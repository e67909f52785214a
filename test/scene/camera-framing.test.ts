// frameBounds / sceneBounds: cameras placed from a scene's bounds. The fit is checked by projecting
// the box corners through a pinhole camera built here from the returned position, target, up and
// field of view: every corner must land inside the image less the margin, and one must touch it.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { frameBounds, lookAtCamera, orbitCamera, sceneBounds, type SceneBounds } from '../../src/scene/camera-framing.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import type { WavefrontCameraInput } from '../../src/scene/types.ts';

const sub = (a: readonly number[], b: readonly number[]): number[] => a.map((v, i) => v - b[i]!);
const dot = (a: readonly number[], b: readonly number[]): number => a.reduce((s, v, i) => s + v * b[i]!, 0);
const cross = (a: readonly number[], b: readonly number[]): number[] => [a[1]! * b[2]! - a[2]! * b[1]!, a[2]! * b[0]! - a[0]! * b[2]!, a[0]! * b[1]! - a[1]! * b[0]!];
const unit = (a: readonly number[]): number[] => a.map((v) => v / Math.hypot(...a));

/** Normalised image coordinates (-1..1 at the image edges) of each box corner. */
function project(camera: WavefrontCameraInput, bounds: SceneBounds, aspect: number): Array<[number, number, number]> {
  const forward = unit(sub(camera.target, camera.position));
  const right = unit(cross(forward, camera.up ?? [0, 1, 0]));
  const up = cross(right, forward);
  const t = Math.tan(((camera.fovYDegrees ?? 45) * Math.PI) / 360);
  const out: Array<[number, number, number]> = [];
  for (let c = 0; c < 8; c++) {
    const p = sub([c & 1 ? bounds.max[0] : bounds.min[0], c & 2 ? bounds.max[1] : bounds.min[1], c & 4 ? bounds.max[2] : bounds.min[2]], camera.position);
    const depth = dot(p, forward);
    out.push([dot(p, right) / (depth * t * aspect), dot(p, up) / (depth * t), depth]);
  }
  return out;
}

const boxes: SceneBounds[] = [
  { min: [-1, 0, -1], max: [3, 2, 0] },
  { min: [-5, -0.01, -5], max: [5, 0.01, 5] }, // a board lying flat
  { min: [-0.5, -0.5, 0], max: [0.5, 0.5, 0] }, // a plane facing +Z
  { min: [100, 200, 300], max: [100.2, 200.1, 300.4] },
];

test('box fit: every corner in view within the margin, one touching it, for views all round', () => {
  for (const bounds of boxes) {
    for (const [azimuthDegrees, elevationDegrees, aspectRatio] of [[30, 25, 1], [0, 0, 1], [-135, 60, 16 / 9], [90, -30, 0.5], [10, 90, 1]] as const) {
      const camera = frameBounds(bounds, { azimuthDegrees, elevationDegrees, aspectRatio });
      const corners = project(camera, bounds, aspectRatio);
      const reach = Math.max(...corners.map(([x, y]) => Math.max(Math.abs(x), Math.abs(y))));
      assert.ok(corners.every(([, , depth]) => depth > 0), 'all corners in front of the eye');
      assert.ok(reach <= 0.95 + 1e-9, `corners reach ${reach} (margin 5 %)`);
      // Flat boxes seen exactly edge-on have only their depth to fit; every other view is tight.
      if (Math.max(...bounds.max.map((v, i) => v - bounds.min[i]!)) > 0.01 && !(elevationDegrees === 0 && bounds === boxes[1])) {
        assert.ok(reach > 0.95 - 1e-6, `the fit is tight (reach ${reach}) at ${azimuthDegrees}/${elevationDegrees}`);
      }
      assert.deepEqual(camera.target, bounds.min.map((v, i) => (v + bounds.max[i]!) / 2));
    }
  }
});

test('orbit direction: azimuth about +Y from +Z towards +X, elevation above the horizon; up stays usable looking down', () => {
  const bounds = boxes[0]!;
  for (const [az, el] of [[0, 0], [90, 0], [30, 25], [-60, -45], [45, 90], [45, -90]] as const) {
    const camera = frameBounds(bounds, { azimuthDegrees: az, elevationDegrees: el });
    const toEye = unit(sub(camera.position, camera.target));
    const [a, e] = [(az * Math.PI) / 180, (el * Math.PI) / 180];
    const expected = [Math.sin(a) * Math.cos(e), Math.sin(e), Math.cos(a) * Math.cos(e)];
    toEye.forEach((v, i) => assert.ok(Math.abs(v - expected[i]!) < 1e-9, `toEye ${toEye} at ${az}/${el}`));
    const up = camera.up!;
    assert.ok(Math.abs(dot(up, toEye)) < 1e-9 && Math.abs(Math.hypot(...up) - 1) < 1e-9, 'up is a unit vector in the image plane');
    if (Math.abs(el) < 90) assert.ok(up[1]! > 0, 'up points upwards');
  }
  // The default: a raised three-quarter view, so a board lying flat is not seen edge-on.
  const board = frameBounds(boxes[1]!);
  const view = unit(sub(board.target, board.position));
  assert.ok(-view[1]! > Math.sin((20 * Math.PI) / 180), `looking down at the board (view ${view})`);
});

test('sphere fit and given distances do not depend on the direction (turntables)', () => {
  const bounds = boxes[0]!;
  const distance = (c: WavefrontCameraInput): number => Math.hypot(...sub(c.position, c.target));
  const sphere = [0, 45, 170].map((az) => distance(frameBounds(bounds, { azimuthDegrees: az, fit: 'sphere' })));
  assert.ok(sphere.every((d) => Math.abs(d - sphere[0]!) < 1e-9), `${sphere}`);
  const radius = Math.hypot(4, 2, 1) / 2;
  assert.ok(Math.abs(sphere[0]! - radius / Math.sin(Math.atan(0.95 * Math.tan(Math.PI / 8)))) < 1e-9);
  assert.ok(Math.abs(distance(orbitCamera(bounds, { azimuthDegrees: 10, elevationDegrees: 5, distance: 7 })) - 7) < 1e-9);
});

test('bad options are typed errors naming the option; a camera looking straight down gets a usable up', () => {
  const throwsOn = (field: string, f: () => unknown): void => {
    assert.throws(f, (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_OPTION' && e.field === field);
  };
  throwsOn('elevationDegrees', () => frameBounds(boxes[0], { elevationDegrees: 91 }));
  throwsOn('fovYDegrees', () => frameBounds(boxes[0], { fovYDegrees: 0 }));
  throwsOn('fovYDegrees', () => frameBounds(boxes[0], { fovYDegrees: 180 }));
  throwsOn('aspectRatio', () => frameBounds(boxes[0], { aspectRatio: -1 }));
  throwsOn('distance', () => frameBounds(boxes[0], { distance: 0 }));
  throwsOn('fit', () => frameBounds(boxes[0], { fit: 'cube' as never }));
  throwsOn('bounds', () => frameBounds({ min: [1, 0, 0], max: [0, 1, 1] }));
  throwsOn('target', () => lookAtCamera([1, 2, 3], [1, 2, 3]));
  assert.deepEqual(lookAtCamera([0, 5, 0], [0, 0, 0]).up, [0, 0, -1]);
  assert.deepEqual(lookAtCamera([0, 0, 5], [0, 0, 0]).up, [0, 1, 0]);
});

test('sceneBounds: instanced meshes (column-major transforms), meshes without instances, analytic objects', () => {
  const mesh = { positions: [0, 0, 0, 1, 0, 0, 0, 1, 0] };
  // Scaled by 2 and moved by (10, 0, -1).
  const transform = [2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 10, 0, -1, 1];
  assert.deepEqual(sceneBounds({ meshes: [mesh], instances: [{ mesh: 0, transform }] }), { min: [10, 0, -1], max: [12, 2, -1] });
  assert.deepEqual(sceneBounds({ meshes: [mesh] }), { min: [0, 0, 0], max: [1, 1, 0] });
  assert.deepEqual(sceneBounds({ sceneObjects: [{ type: 'sphere', center: [0, 1, 0], radius: 2 }, { type: 'box', min: [3, 3, 3], max: [4, 4, 4] }] }), { min: [-2, -1, -2], max: [4, 4, 4] });
  assert.equal(sceneBounds({}), undefined);
});
