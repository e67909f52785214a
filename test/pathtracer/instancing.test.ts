// Two-level acceleration (pathtracer/scene/instancing.ts): placements traced through bottom-level
// trees render what the same placements flattened into world-space triangles render, under
// rotations, non-uniform and mirroring scales, single-sided and alpha-masked materials, material
// overrides and emissive placements (each its own light). Same seed: the same paths, so the pixels
// agree to float rounding (object-space intersection rounds differently); other seeds: agreement
// within the standard error.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import type { InstancingMode, WavefrontPathTracingOptions, WavefrontRendererSnapshot } from '../../src/index.ts';
import { testDevice } from '../helpers/gpu.ts';
import { meanDifferenceZ, relativeL1 } from '../helpers/image-stats.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { checkBufferLimits, planBuffers } from '../../src/pathtracer/buffer-plan.ts';
import { createWavefrontPathTracingComputeConfig } from '../../src/pathtracer/config.ts';
import { planInput } from '../../src/pathtracer/scene-plan.ts';
import { normalizeWavefrontScene } from '../../src/scene/normalize-scene.ts';
import { transformsCamera, transformsScene, trs } from './instancing-scenes.ts';

const SIZE = 48;

async function render(instancing: InstancingMode, seed: number, spp: number, extra: Partial<WavefrontPathTracingOptions> = {}): Promise<{ image: Float32Array; stats: WavefrontRendererSnapshot }> {
  const device = await testDevice();
  const renderer = await createWavefrontPathTracingComputeRenderer({
    device, width: SIZE, height: SIZE, maxDepth: 4, samplesPerPixel: spp, seed, instancing,
    ...transformsScene(), camera: transformsCamera, environment: { color: [0.15, 0.17, 0.2] }, ...extra,
  });
  try {
    const frame = await renderer.renderFrame();
    assert.equal(frame.invalidSamples, 0);
    return { image: (await renderer.readRadiance()).data, stats: renderer.getSnapshot() };
  } finally {
    renderer.destroy();
  }
}

test('placements through bottom levels render the flattened image: same seed to rounding, other seeds within noise', async () => {
  const flat = await render('off', 3, 16);
  const shared = await render('always', 3, 16);
  assert.equal(flat.stats.instancing.placements, 0);
  assert.equal(shared.stats.instancing.placements, 12);
  // Ground, sphere, single-sided wedge, the card under two materials, the panel.
  assert.equal(shared.stats.instancing.sharedMeshes, 6);
  assert.equal(shared.stats.instancing.topLevelRecords, 12);
  let sum = 0, diff = 0, far = 0;
  for (let i = 0; i < flat.image.length; i += 4) {
    for (let c = 0; c < 3; c++) {
      const a = flat.image[i + c]!, b = shared.image[i + c]!;
      sum += a;
      diff += Math.abs(a - b);
      if (Math.abs(a - b) > 0.05 * Math.max(a, b) + 1e-3) far++;
    }
  }
  const pixels = (3 * flat.image.length) / 4;
  assert.ok(diff / sum < 0.02, `relative L1 difference ${(diff / sum).toFixed(4)} at the same seed`);
  assert.ok(far < 0.03 * pixels, `${far} of ${pixels} channel values differ by more than 5%`);
  const other = await render('always', 11, 16);
  const z = meanDifferenceZ(flat.image, other.image);
  assert.ok(z.every((v) => Math.abs(v) < 4), `mean difference z = ${z.map((v) => v.toFixed(2)).join(', ')}`);
});

/** The scene moved: every placement turned and shifted, and (`meshes`) the shared sphere mesh inflated by 10 %. */
function movedScene(meshes = true): ReturnType<typeof transformsScene> {
  const s = transformsScene();
  const turn = trs([0.15, 0, -0.1], [0, 1, 0], 0.35, [1, 1, 1]);
  return {
    ...s,
    meshes: s.meshes.map((m, i) => (meshes && i === 1 ? { ...m, positions: Array.from(m.positions, (v) => 1.1 * v) } : m)),
    instances: s.instances.map((inst, i) => (i === 0 ? inst : { ...inst, transform: multiply(turn, inst.transform!) })),
  };
}

function multiply(a: ArrayLike<number>, b: ArrayLike<number>): number[] {
  const out = new Array<number>(16).fill(0);
  for (let c = 0; c < 4; c++) for (let r = 0; r < 4; r++) for (let k = 0; k < 4; k++) out[4 * c + r]! += a[4 * k + r]! * b[4 * c + k]!;
  return out;
}

// Moving meshes takes the full path (flatten, pack, refit or rebuild); moving instances only with a
// refit patches the moved records (top-level-patch.ts), placements ('always') and flattened
// instances ('off') alike.
const moves = [
  { instancing: 'always', accelerationBuildMode: 'cpu-upload', bvh: 'refit', meshes: true },
  { instancing: 'always', accelerationBuildMode: 'cpu-upload', bvh: 'rebuild', meshes: true },
  { instancing: 'always', accelerationBuildMode: 'gpu', bvh: 'refit', meshes: true },
  { instancing: 'always', accelerationBuildMode: 'cpu-upload', bvh: 'refit', meshes: false },
  { instancing: 'off', accelerationBuildMode: 'gpu', bvh: 'refit', meshes: false },
] as const;
for (const { instancing, accelerationBuildMode, bvh, meshes } of moves) {
  test(`moving placements${meshes ? ' and a shared mesh' : ' only'} ('${instancing}', ${accelerationBuildMode}, ${bvh}): the image of a renderer created with the moved scene`, async () => {
    const device = await testDevice();
    const base = { device, width: SIZE, height: SIZE, maxDepth: 4, samplesPerPixel: 8, seed: 9, instancing, accelerationBuildMode, camera: transformsCamera, environment: { color: [0.15, 0.17, 0.2] as [number, number, number] } };
    const renderer = await createWavefrontPathTracingComputeRenderer({ ...base, ...transformsScene() });
    const fresh = await createWavefrontPathTracingComputeRenderer({ ...base, ...movedScene(meshes) });
    try {
      await renderer.renderFrame();
      const before = (await renderer.readRadiance()).data;
      const moved = movedScene(meshes);
      const stats = await renderer.updateGeometry({
        ...(meshes ? { meshes: moved.meshes.map((m, i) => (i === 1 ? { positions: m.positions } : null)) } : {}),
        instances: moved.instances.map((inst) => ({ transform: inst.transform ?? [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1] })),
        bvh,
      });
      assert.equal(stats.bvh, bvh);
      assert.equal(stats.topLevel, bvh === 'rebuild' || meshes ? 'flattened' : 'patched');
      // Patched: one record per placement given a transform ('always'), each of their triangles ('off').
      const instances = moved.instances.length;
      if (stats.topLevel === 'patched' && instancing === 'always') assert.equal(stats.topLevelRecordsWritten, instances);
      if (stats.topLevel === 'patched' && instancing === 'off') assert.ok(stats.topLevelRecordsWritten > instances, `${stats.topLevelRecordsWritten} records`);
      await renderer.renderFrame();
      await fresh.renderFrame();
      const updated = (await renderer.readRadiance()).data;
      const want = (await fresh.readRadiance()).data;
      assert.ok(relativeL1(updated, want) < 0.005, `updated vs created moved: relative L1 ${relativeL1(updated, want).toFixed(5)}`);
      assert.ok(relativeL1(before, want) > 0.1, 'the update moved something');
    } finally {
      renderer.destroy();
      fresh.destroy();
    }
  });
}

test('the megakernel traces placements through bottom levels too', async () => {
  const flat = await render('off', 4, 8, { integrator: 'megakernel' });
  const shared = await render('always', 4, 8, { integrator: 'megakernel' });
  assert.equal(shared.stats.integrator, 'megakernel');
  assert.ok(relativeL1(flat.image, shared.image) < 0.02, `relative L1 ${relativeL1(flat.image, shared.image).toFixed(4)}`);
});

test("'auto' shares a mesh placed often enough, flattens the rest; bad placements are typed errors naming the field", async () => {
  const device = await testDevice();
  const s = transformsScene();
  // 40 more placements of the 320-triangle sphere: 13,440 added triangles if flattened.
  const many = { ...s, instances: [...s.instances, ...Array.from({ length: 40 }, (_, i) => ({ mesh: 1, transform: trs([-2 + 0.1 * i, 0.3, -2], [0, 1, 0], i, [0.3, 0.3, 0.3]) }))] };
  const auto = await createWavefrontPathTracingComputeRenderer({ device, width: 8, height: 8, camera: transformsCamera, ...many });
  try {
    const stats = auto.getSnapshot().instancing;
    assert.equal(stats.mode, 'auto');
    assert.equal(stats.sharedMeshes, 1, 'only the sphere is shared');
    assert.equal(stats.placements, 44);
    assert.equal(stats.bottomLevelTriangles, 320);
    assert.equal(stats.placedTriangles, 44 * 320);
    await assert.rejects(auto.updateGeometry({ instances: many.instances.map((_, i) => (i === 2 ? { transform: [NaN, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1] } : null)) }), (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_INSTANCE' && e.field === 'instances[2].transform[0]');
  } finally {
    auto.destroy();
  }
  const bad = (instances: unknown[]): Promise<unknown> => createWavefrontPathTracingComputeRenderer({ device, width: 8, height: 8, ...s, instances: instances as never });
  const rejects = async (instances: unknown[], code: string, field: string): Promise<void> => {
    await assert.rejects(bad(instances), (e: unknown) => e instanceof GpuRendererError && e.code === code && e.field === field, `${code} at ${field}`);
  };
  await rejects([{ mesh: 1, transform: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, Infinity, 0, 0, 1] }], 'INVALID_INSTANCE', 'instances[0].transform[12]');
  await rejects([{ mesh: 1 }, { mesh: 1, transform: [1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1] }], 'INVALID_INSTANCE', 'instances[1].transform');
  await rejects([{ mesh: 7 }], 'INVALID_INSTANCE', 'instances[0].mesh');
  await rejects([{ mesh: 1, material: 3 }], 'INVALID_INSTANCE', 'instances[0].material');
});

test('SCENE_TOO_LARGE names what does not fit and by how much: the instance records, or flattened triangles', () => {
  const scene = normalizeWavefrontScene({ ...transformsScene(), instances: Array.from({ length: 250_000 }, (_, i) => ({ mesh: 1, transform: trs([i, 0, 0], [0, 1, 0], 0, [1, 1, 1]) })) });
  const limits = { maxStorageBufferBindingSize: 32 * 2 ** 20, maxBufferSize: 2 ** 30 } as GPUSupportedLimits;
  const plan = (instancing: InstancingMode): Parameters<typeof checkBufferLimits>[1] => planBuffers(planInput(createWavefrontPathTracingComputeConfig({ width: 8, height: 8, instancing }), scene));
  assert.throws(() => checkBufferLimits(limits, plan('always')), (e: unknown) => e instanceof GpuRendererError && e.code === 'SCENE_TOO_LARGE' && e.field === 'instances' && /instance buffer needs \d+ bytes .*too many/.test(e.message));
  assert.throws(() => checkBufferLimits(limits, plan('off')), (e: unknown) => e instanceof GpuRendererError && e.code === 'SCENE_TOO_LARGE' && e.field === 'meshes' && /80000000 flattened triangles/.test(e.message));
});
