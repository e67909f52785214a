// Environment portals change only how the environment is sampled: a room lit through a window by
// an HDRI renders the same image without portals, with 'guide' and with 'guide-and-gate' portals,
// within noise, and the portals lower the noise.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import type { WavefrontMeshInput } from '../../src/scene/types.ts';
import type { WavefrontPathTracingOptions } from '../../src/pathtracer/types.ts';
import { testDevice } from '../helpers/gpu.ts';
import { mapOption, testHdri } from '../lighting/gpu-fixtures.ts';

type Quad = [number[], number[], number[], number[]];

/** A closed 4 x 2.4 x 4 room with a window in its +x wall (y in [0.8, 1.8], z in [-0.7, 0.7]). */
function roomWithWindow(): WavefrontMeshInput[] {
  const quads: Quad[] = [
    [[-2, 0, -2], [2, 0, -2], [2, 0, 2], [-2, 0, 2]], // floor
    [[-2, 2.4, -2], [-2, 2.4, 2], [2, 2.4, 2], [2, 2.4, -2]], // ceiling
    [[-2, 0, -2], [-2, 0, 2], [-2, 2.4, 2], [-2, 2.4, -2]], // -x wall
    [[-2, 0, -2], [-2, 2.4, -2], [2, 2.4, -2], [2, 0, -2]], // -z wall
    [[-2, 0, 2], [2, 0, 2], [2, 2.4, 2], [-2, 2.4, 2]], // +z wall
    // +x wall around the window
    [[2, 0, -2], [2, 0.8, -2], [2, 0.8, 2], [2, 0, 2]],
    [[2, 1.8, -2], [2, 2.4, -2], [2, 2.4, 2], [2, 1.8, 2]],
    [[2, 0.8, -2], [2, 1.8, -2], [2, 1.8, -0.7], [2, 0.8, -0.7]],
    [[2, 0.8, 0.7], [2, 1.8, 0.7], [2, 1.8, 2], [2, 0.8, 2]],
  ];
  const positions: number[] = [];
  const indices: number[] = [];
  for (const q of quads) {
    const base = positions.length / 3;
    for (const v of q) positions.push(...v);
    indices.push(base, base + 1, base + 2, base, base + 2, base + 3);
  }
  return [{ positions, indices, material: { baseColorFactor: [0.7, 0.7, 0.7, 1], metallicFactor: 0, roughnessFactor: 1, ior: 1, doubleSided: true } }];
}

/** The window as a portal: cross(edgeU, edgeV) = +x points out of the room. */
const windowPortal = { center: [2, 1.3, 0], edgeU: [0, 1, 0], edgeV: [0, 0, 1.4] };

const size = 24;
const camera = { position: [-1.8, 1.6, 1.7], target: [0.5, 0.5, -0.5], up: [0, 1, 0], fovYDegrees: 70 };

async function renderRoom(options: Partial<WavefrontPathTracingOptions>, seed: number, spp: number): Promise<Float32Array> {
  const device = await testDevice();
  const renderer = await createWavefrontPathTracingComputeRenderer({
    device, width: size, height: size, samplesPerPixel: spp, seed, maxDepth: 4, camera, meshes: roomWithWindow(), environmentMap: mapOption(testHdri(64, 32, 50)), ...options,
  });
  try {
    const stats = await renderer.renderFrame();
    assert.equal(stats.invalidSamples, 0);
    return (await renderer.readRadiance()).data;
  } finally {
    renderer.destroy();
  }
}

function quadrants(image: Float32Array): number[] {
  const q = [0, 0, 0, 0];
  for (let y = 0; y < size; y++) for (let x = 0; x < size; x++) for (let c = 0; c < 3; c++) q[2 * Math.floor((2 * y) / size) + Math.floor((2 * x) / size)]! += image[4 * (y * size + x) + c]!;
  return q.map((v) => v / ((size * size) / 4) / 3);
}

/** Mean squared difference of two independent renders: twice the per-pixel variance. */
function pixelVariance(a: Float32Array, b: Float32Array): number {
  let s = 0;
  for (let k = 0; k < size * size; k++) for (let c = 0; c < 3; c++) s += (a[4 * k + c]! - b[4 * k + c]!) ** 2;
  return s / (2 * 3 * size * size);
}

test('a room lit through a window renders the same with and without portals; portals lower the variance', async () => {
  const spp = 128;
  const plain = await renderRoom({}, 1, spp);
  const plain2 = await renderRoom({}, 2, spp);
  const guide = await renderRoom({ environmentPortals: [windowPortal] }, 3, spp);
  const guide2 = await renderRoom({ environmentPortals: [windowPortal] }, 4, spp);
  const gate = await renderRoom({ environmentPortals: [windowPortal], environmentPortalMode: 'guide-and-gate' }, 5, spp);
  const reference = quadrants(plain).map((v, i) => (v + quadrants(plain2)[i]!) / 2);
  for (const [name, image] of [['guide', guide], ['guide-and-gate', gate]] as const) {
    quadrants(image).forEach((v, i) => {
      assert.ok(Math.abs(v - reference[i]!) < 0.05 * reference[i]!, `${name} quadrant ${i}: ${v} vs ${reference[i]} without portals`);
    });
  }
  const mean = reference.reduce((a, b) => a + b, 0) / 4;
  assert.ok(mean > 0.01, `the room is lit (${mean})`);
  const varPlain = pixelVariance(plain, plain2);
  const varGuide = pixelVariance(guide, guide2);
  assert.ok(varGuide < 0.8 * varPlain, `variance with portals ${varGuide} vs without ${varPlain}`);
});
