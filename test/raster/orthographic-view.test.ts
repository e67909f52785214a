// An orthographic camera's rays are parallel: every fragment is seen along the view axis. A large
// glossy plane facing the camera, lit head-on by a directional light, then has one radiance
// everywhere (n = v = l = h at every point), the radiance of the same plane seen head-on by a
// perspective camera at the image centre. Viewing each fragment from the eye point instead tilts v
// towards the plane's edges and dims the highlight there.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createRasterRenderer } from '../../src/raster/index.ts';
import { testDevice } from '../helpers/gpu.ts';
import { quad } from './scenes.ts';
import type { WavefrontCameraInput } from '../../src/scene/types.ts';

const size = 32;
const material = { baseColorFactor: [0, 0, 0, 1], metallicFactor: 0, roughnessFactor: 0.3, ior: 1.5 };

async function render(camera: WavefrontCameraInput): Promise<ArrayLike<number>> {
  const renderer = await createRasterRenderer({
    device: await testDevice(),
    width: size,
    height: size,
    toneMapping: 'linear',
    shadow: false,
    camera,
    lights: [{ type: 'directional', direction: [0, 0, -1], intensity: 1 }],
    meshes: [{ ...quad(4), material }],
  });
  try {
    await renderer.render();
    return (await renderer.readPixels()).data;
  } finally {
    renderer.destroy();
  }
}

test('orthographic raster camera: a glossy plane lit head-on has the same radiance in every pixel, as seen head-on in perspective', async () => {
  // The eye is 0.5 in front of an 8 x 8 plane that fills the view: the eye point sees the corners at 83 degrees.
  const ortho = await render({ type: 'orthographic', position: [0, 0, 0.5], target: [0, 0, 0], orthographicHeight: 6 });
  const perspective = await render({ type: 'perspective', position: [0, 0, 3], target: [0, 0, 0], fovYDegrees: 1 });
  const centre = perspective[4 * ((size / 2) * size + size / 2)]!;
  assert.ok(centre > 40 && centre < 250, `head-on highlight ${centre} (neither black nor clipped)`);
  for (let p = 0; p < size * size; p++) {
    assert.ok(Math.abs(ortho[4 * p]! - centre) <= 2, `pixel (${p % size}, ${Math.floor(p / size)}): ${ortho[4 * p]} vs ${centre} head-on`);
  }
});
