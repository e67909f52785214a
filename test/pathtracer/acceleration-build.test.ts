// accelerationBuildMode 'gpu' and updateGeometry end to end: the path tracer over the GPU-built
// LBVH renders the image of the CPU-built tree (same seed: the same paths, so the same pixels; other
// seeds: agreement within the standard error), and a scene moved by updateGeometry (vertices,
// instance transforms, the light) renders exactly what a renderer created with the moved scene
// renders, whether the BVH was refitted or rebuilt, in either build mode.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import { createCornellBoxScene } from '../../src/scene/cornell-box.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import type { AccelerationBuildMode, WavefrontMeshInput, WavefrontPathTracingOptions, WavefrontPathTracingRenderer } from '../../src/index.ts';
import { testDevice } from '../helpers/gpu.ts';
import { meanDifferenceZ } from '../helpers/image-stats.ts';

const SIZE = 32;

/** A hanging cloth: an n x n grid in the middle of the box, displaced by a wave of the given phase (flat shaded). */
function cloth(phase: number, n = 12): WavefrontMeshInput {
  const positions: number[] = [];
  const indices: number[] = [];
  for (let j = 0; j <= n; j++) {
    for (let i = 0; i <= n; i++) {
      const u = i / n, v = j / n;
      positions.push(-0.6 + 1.2 * u, -0.2 + 0.9 * v, 0.35 + 0.25 * Math.sin(6 * u + phase) * Math.sin(3 * v + 0.5 * phase));
    }
  }
  for (let j = 0; j < n; j++) {
    for (let i = 0; i < n; i++) {
      const a = j * (n + 1) + i;
      indices.push(a, a + 1, a + n + 2, a, a + n + 2, a + n + 1);
    }
  }
  return { id: 'cloth', positions, indices, material: { baseColorFactor: [0.2, 0.5, 0.8], metallicFactor: 0, roughnessFactor: 0.5 } };
}

const translate = (x: number, y: number, z: number): number[] => [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, x, y, z, 1];

/** The Cornell box with the cloth; pose 1 moves the cloth, the short block and the light. */
function scene(pose: 0 | 1): Partial<WavefrontPathTracingOptions> {
  const box = createCornellBoxScene();
  const meshes = [...box.meshes!, cloth(pose === 0 ? 0 : 1.7)];
  const instances = meshes.map((_, mesh) => ({
    mesh,
    transform: pose === 1 && mesh === 5 ? translate(0.1, 0, 0.15) : pose === 1 && mesh === 7 ? translate(-0.2, 0, 0.1) : translate(0, 0, 0),
  }));
  return { meshes, instances, camera: box.camera, environment: box.environment! };
}

async function create(mode: AccelerationBuildMode, pose: 0 | 1, seed: number, spp: number): Promise<WavefrontPathTracingRenderer> {
  const device = await testDevice();
  return createWavefrontPathTracingComputeRenderer({ device, width: SIZE, height: SIZE, maxDepth: 5, samplesPerPixel: spp, seed, tileSize: 32, accelerationBuildMode: mode, ...scene(pose) });
}

async function image(renderer: WavefrontPathTracingRenderer): Promise<Float32Array> {
  const stats = await renderer.renderFrame();
  assert.equal(stats.invalidSamples, 0);
  return (await renderer.readRadiance()).data;
}

async function render(mode: AccelerationBuildMode, pose: 0 | 1, seed: number, spp: number): Promise<Float32Array> {
  const renderer = await create(mode, pose, seed, spp);
  try {
    return await image(renderer);
  } finally {
    renderer.destroy();
  }
}

/**
 * Same seed, same scene, another tree: every path draws the same numbers and finds the same hits,
 * so pixels agree to float rounding. Exact ties (a ray through the shared edge of two coplanar
 * triangles) may resolve to the other triangle, which moves a path by an ulp; such pixels must be
 * rare and close.
 */
function assertSamePaths(a: Float32Array, b: Float32Array, what: string): string {
  let differing = 0;
  let maxRelative = 0;
  for (let i = 0; i < a.length; i++) {
    if (a[i] === b[i]) continue;
    differing++;
    maxRelative = Math.max(maxRelative, Math.abs(a[i]! - b[i]!) / Math.max(1e-3, Math.abs(a[i]!)));
  }
  assert.ok(differing <= 0.002 * a.length, `${what}: ${differing} of ${a.length} values differ (max relative ${maxRelative})`);
  const z = meanDifferenceZ(a, b);
  z.forEach((zc, c) => assert.ok(!(Math.abs(zc) > 3), `${what}: channel ${c} mean difference z = ${zc}`));
  return `${what}: ${differing} of ${a.length} values differ (max relative ${maxRelative.toExponential(1)})`;
}

test("accelerationBuildMode 'gpu' renders the CPU build's image: same seed, same paths; other seeds, within the standard error (|z| < 4)", async (t) => {
  const gpu = await create('gpu', 0, 7, 8);
  try {
    const snapshot = gpu.getSnapshot();
    assert.ok(snapshot.bvhNodeCount >= 3 && snapshot.bvhDepth >= 2, `GPU tree: ${snapshot.bvhNodeCount} nodes, depth ${snapshot.bvhDepth}`);
    const gpuImage = await image(gpu);
    const cpuSameSeed = await render('cpu-upload', 0, 7, 8);
    t.diagnostic(assertSamePaths(gpuImage, cpuSameSeed, 'same seed'));
    const cpuOtherSeed = await render('cpu-upload', 0, 8, 8);
    meanDifferenceZ(gpuImage, cpuOtherSeed).forEach((z, c) => assert.ok(Math.abs(z) < 4, `other seed: channel ${c}: z = ${z}`));
    let lum = 0;
    for (let i = 0; i < gpuImage.length; i += 4) lum += gpuImage[i]!;
    assert.ok(lum / (SIZE * SIZE) > 0.05, 'the image is lit');
  } finally {
    gpu.destroy();
  }
});

/** Pose 1 as an update of pose 0: new cloth vertices, the short block and the light moved. */
function poseUpdate(bvh: 'refit' | 'rebuild'): Parameters<WavefrontPathTracingRenderer['updateGeometry']>[0] {
  const next = scene(1);
  return {
    meshes: next.meshes!.map((m, i) => (i === 8 ? { positions: m.positions } : null)),
    instances: next.instances!.map((inst) => ({ transform: inst.transform! })),
    bvh,
  };
}

for (const [mode, bvh] of [['gpu', 'refit'], ['cpu-upload', 'refit'], ['gpu', 'rebuild']] as const) {
  test(`updateGeometry (${mode}, ${bvh}) renders what a renderer created with the moved scene renders`, async (t) => {
    const moved = await create(mode, 0, 5, 4);
    try {
      await image(moved);
      const stats = await moved.updateGeometry(poseUpdate(bvh));
      assert.equal(stats.bvh, bvh);
      assert.equal(moved.getSnapshot().samplesAccumulated, 0, 'the accumulation restarts');
      const updated = await image(moved);
      const fresh = await render('cpu-upload', 1, 5, 4);
      t.diagnostic(assertSamePaths(updated, fresh, `${mode} ${bvh}`));
      // The update really moved something: pose 0 looks different.
      const before = await render('cpu-upload', 0, 5, 4);
      let changed = 0;
      for (let i = 0; i < before.length; i++) if (Math.abs(before[i]! - fresh[i]!) > 1e-3) changed++;
      assert.ok(changed > 0.05 * before.length, `pose 1 differs from pose 0 (${changed} values)`);
    } finally {
      moved.destroy();
    }
  });
}

test('updateGeometry refuses bad updates with typed errors naming the field, and keeps the scene', async () => {
  const renderer = await create('gpu', 0, 1, 1);
  try {
    await renderer.renderFrame();
    const cases: Array<[unknown, string, string]> = [
      [{ meshes: [null] }, 'INVALID_MESH', 'meshes'],
      [{ meshes: [...Array(8).fill(null), { positions: [0, 0, 0] }] }, 'INVALID_MESH', 'meshes[8].positions'],
      [{ meshes: [...Array(8).fill(null), { positions: scene(1).meshes![8]!.positions, uvs: [] }] }, 'INVALID_MESH', 'meshes[8].uvs'],
      [{ meshes: [...Array(8).fill(null), { positions: scene(1).meshes![8]!.positions, normals: scene(1).meshes![8]!.positions }] }, 'INVALID_MESH', 'meshes[8].normals'],
      [{ meshes: [...Array(8).fill(null), { positions: Array.from(scene(1).meshes![8]!.positions, (v, i) => (i === 4 ? NaN : v)) }] }, 'INVALID_MESH', 'meshes[8].positions[4]'],
      [{ instances: Array(9).fill({ transform: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 2] }) }, 'INVALID_INSTANCE', 'instances[0].transform'],
      [{ bvh: 'sometimes' }, 'INVALID_OPTION', 'bvh'],
      [{ colour: 1 }, 'INVALID_OPTION', 'colour'],
    ];
    for (const [update, code, field] of cases) {
      await assert.rejects(
        renderer.updateGeometry(update as never),
        (e: unknown) => e instanceof GpuRendererError && e.code === code && e.field === field,
        `${JSON.stringify(update).slice(0, 80)} -> ${code} at ${field}`,
      );
    }
    assert.equal(renderer.getSnapshot().samplesAccumulated, 1, 'refused updates leave the accumulation alone');
  } finally {
    renderer.destroy();
  }
  const device = await testDevice();
  await assert.rejects(
    createWavefrontPathTracingComputeRenderer({ device, width: 8, height: 8, accelerationBuildMode: 'gpu-only' as never, meshes: [cloth(0)] }),
    (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_OPTION' && e.field === 'accelerationBuildMode',
  );
});
