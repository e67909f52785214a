// glTF's `doubleSided: false` (glTF 2.0 section 3.9.5: back-face culling) for the path tracer's
// camera rays: a single-sided quad is invisible from behind and visible from the front; mirroring
// instances keep their front face; a double-sided quad is visible from both sides. Secondary rays
// still meet both faces (bvh-traversal.wesl says why): the culled quad keeps its shadow.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import type { WavefrontCameraInput, WavefrontMaterialInput, WavefrontMeshInput, WavefrontInstanceInput } from '../../src/scene/types.ts';
import { testDevice } from '../helpers/gpu.ts';

const size = 8;
const L = [1, 1, 1];
// Lambertian (ior 1, metallic 0): under a uniform environment it renders baseColor L exactly.
const red = [0.8, 0.2, 0.1] as const;
const lambert = (doubleSided: boolean): WavefrontMaterialInput => ({ baseColorFactor: [...red], metallicFactor: 0, roughnessFactor: 1, ior: 1, doubleSided });
/** A quad in the plane z = 0, counter-clockwise seen from +z (its front face), covering the view. */
const quad = (material: WavefrontMaterialInput): WavefrontMeshInput => ({ positions: [-2, -2, 0, 2, -2, 0, 2, 2, 0, -2, 2, 0], indices: [0, 1, 2, 0, 2, 3], material });
const from = (z: number): WavefrontCameraInput => ({ type: 'orthographic', position: [0.1, 0.2, z], target: [0.1, 0.2, 0], up: [0, 1, 0], orthographicHeight: 1 });

async function meanColor(meshes: WavefrontMeshInput[], camera: WavefrontCameraInput, instances?: WavefrontInstanceInput[], spp = 16): Promise<number[]> {
  const device = await testDevice();
  const renderer = await createWavefrontPathTracingComputeRenderer({
    device, width: size, height: size, samplesPerPixel: spp, seed: 9, maxDepth: 4, camera, environment: { color: L }, meshes, ...(instances ? { instances } : {}),
  });
  try {
    const stats = await renderer.renderFrame();
    assert.equal(stats.invalidSamples, 0);
    const { data } = await renderer.readRadiance();
    const mean = [0, 0, 0];
    for (let p = 0; p < size * size; p++) for (let c = 0; c < 3; c++) mean[c]! += data[4 * p + c]! / (size * size);
    return mean;
  } finally {
    renderer.destroy();
  }
}

const near = (got: number[], want: readonly number[], what: string, tolerance = 0.03): void => {
  for (let c = 0; c < 3; c++) assert.ok(Math.abs(got[c]! - want[c]!) <= tolerance * want[c]!, `${what}, channel ${c}: ${got[c]} vs ${want[c]}`);
};

test('camera rays: a single-sided quad shows from the front and vanishes from behind; double-sided shows from both', async () => {
  const surface = red.map((r, c) => r * L[c]!);
  near(await meanColor([quad(lambert(false))], from(3)), surface, 'single-sided, front');
  near(await meanColor([quad(lambert(false))], from(-3)), L, 'single-sided, behind: the environment', 1e-6);
  near(await meanColor([quad(lambert(true))], from(-3)), surface, 'double-sided, behind');
  // A mirroring instance (x -> -x) turns the winding clockwise in world space; its front face still
  // faces +z (glTF 2.0 section 3.7.4).
  const mirrored: WavefrontInstanceInput[] = [{ mesh: 0, transform: [-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1] }];
  near(await meanColor([quad(lambert(false))], from(3), mirrored), surface, 'mirrored, front');
  near(await meanColor([quad(lambert(false))], from(-3), mirrored), L, 'mirrored, behind: the environment', 1e-6);
});

/** Form factor from a point to the rectangle [0, a] x [0, b] at height h above its corner (a differential area facing it). */
function cornerFormFactor(a: number, b: number, h: number): number {
  const [x, y] = [a / h, b / h];
  const sx = Math.sqrt(1 + x * x);
  const sy = Math.sqrt(1 + y * y);
  return ((x / sx) * Math.atan(y / sx) + (y / sy) * Math.atan(x / sy)) / (2 * Math.PI);
}

test('secondary rays still meet back faces: a single-sided occluder the camera cannot see keeps its shadow', async (t) => {
  // A white Lambertian floor (z = 0, facing up) under a black single-sided square at height h facing
  // down, seen from above (the square's back): the camera sees the floor through the square, lit by
  // the sky the square does not hide. At (x, y) that is L (1 - F) with F the square's form factor
  // (sum of four corner rectangles). Were the square visible the pixels would be black; were it
  // culled for every ray the floor would be unshadowed (L).
  const h = 0.3;
  const floor: WavefrontMeshInput = { positions: [-9, -9, 0, 9, -9, 0, 9, 9, 0, -9, 9, 0], indices: [0, 1, 2, 0, 2, 3], material: { baseColorFactor: [1, 1, 1], metallicFactor: 0, roughnessFactor: 1, ior: 1 } };
  const occluder: WavefrontMeshInput = { positions: [-1, -1, h, -1, 1, h, 1, 1, h, 1, -1, h], indices: [0, 1, 2, 0, 2, 3], material: { baseColorFactor: [0, 0, 0], metallicFactor: 0, roughnessFactor: 1, ior: 1 } };
  const view = 0.5;
  const under = await meanColor([floor, occluder], { type: 'orthographic', position: [0, 0, 3], target: [0, 0, 0], up: [0, 1, 0], orthographicHeight: view }, undefined, 64);
  let expected = 0;
  const n = 64;
  for (let i = 0; i < n; i++) {
    for (let j = 0; j < n; j++) {
      const x = ((i + 0.5) / n - 0.5) * view;
      const y = ((j + 0.5) / n - 0.5) * view;
      const f = cornerFormFactor(1 - x, 1 - y, h) + cornerFormFactor(1 + x, 1 - y, h) + cornerFormFactor(1 - x, 1 + y, h) + cornerFormFactor(1 + x, 1 + y, h);
      expected += (1 - f) / (n * n);
    }
  }
  t.diagnostic(`floor under the culled square: ${under.map((v) => v.toFixed(4))}, closed form ${expected.toFixed(4)}`);
  for (let c = 0; c < 3; c++) assert.ok(Math.abs(under[c]! - expected * L[c]!) < 0.02, `channel ${c}: ${under[c]} vs ${expected * L[c]!}`);
});
