// Posed glTF frames rendered: the path tracer's CPU-skinned frame covers the pixels the raster
// renderer's GPU-skinned pose of the same time covers; a morphed plane's shading normals (normal
// AOV) follow its morph-target normals and it is lit, not black; updateScene gives the image a new
// renderer gives, grows its buffers when it must, and refuses what its kernels cannot draw.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { loadGltfScene } from '../../src/io/gltf/load-gltf-scene.ts';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { testDevice } from '../helpers/gpu.ts';
import { createBendingTube, createMorphedPlane, PATCH_NORMAL_DELTA } from './fixtures.ts';
import { coverage, createRasterPoser, iou, redMask } from './raster-pose.ts';

// Every renderer of this file but one shares the first's shader features (emitters, no environment),
// so the kernels compile twice in all.
const W = 64;
const H = 64;

test('the path-traced pose at t covers what the raster renderer\'s pose at t covers, and the pose changes with t', async () => {
  const device = await testDevice();
  const { document } = createBendingTube();
  const scene = await loadGltfScene(document, { animation: 'Bend', camera: 'Front' });
  const raster = await createRasterPoser(device, document, scene.materials, W, H);
  const tracer = await createWavefrontPathTracingComputeRenderer({ ...scene, device, width: W, height: H, samplesPerPixel: 16, maxDepth: 1, toneMapping: 'linear' });
  try {
    const traced: Uint8Array[] = [];
    for (const time of [0.2, 0.8]) {
      const posed = await scene.pose({ time });
      await tracer.updateScene({ meshes: posed.meshes, instances: posed.instances, camera: posed.camera });
      await tracer.renderFrame();
      const mask = redMask((await tracer.readPixels()).data);
      const reference = await raster.maskAt('Bend', time, posed.camera);
      assert.ok(coverage(reference) > 80, `raster coverage ${coverage(reference)}`);
      assert.ok(iou(mask, reference) > 0.9, `t = ${time}: IoU ${iou(mask, reference).toFixed(3)} (path traced ${coverage(mask)} px, raster ${coverage(reference)} px)`);
      traced.push(mask);
    }
    assert.ok(iou(traced[0]!, traced[1]!) < 0.8, `the poses at 0.2 s and 0.8 s differ (IoU ${iou(traced[0]!, traced[1]!).toFixed(3)})`);
  } finally {
    tracer.destroy();
    raster.destroy();
  }
});

test('a morphed plane\'s shading normals are its morph-target normals, and the patch is lit like the rest', async () => {
  const device = await testDevice();
  const scene = await loadGltfScene(createMorphedPlane(), { animation: 'Raise', time: 0.5 });
  const size = 32;
  const renderer = await createWavefrontPathTracingComputeRenderer({
    ...scene,
    device,
    width: size,
    height: size,
    samplesPerPixel: 64,
    maxDepth: 2,
    aovs: true,
    environment: { color: [1, 1, 1] },
    // Looking straight down at the plane, which fills [-1, 1]^2 of the view.
    camera: { type: 'orthographic', position: [0, 5, 0], target: [0, 0, 0], up: [0, 0, -1], orthographicHeight: 2 },
  });
  try {
    await renderer.renderFrame();
    const normals = (await renderer.readAov('normal')).data;
    const radiance = (await renderer.readRadiance()).data;
    const len = Math.hypot(0.5 * PATCH_NORMAL_DELTA[0], 1);
    const expectedPatch = [(0.5 * PATCH_NORMAL_DELTA[0]) / len, 1 / len, 0];
    let patchLight = 0, patchCount = 0, outsideLight = 0, outsideCount = 0;
    for (let y = 0; y < size; y++) {
      for (let x = 0; x < size; x++) {
        // Pixel centre in world x/z: x right, z down the image (up is -Z).
        const wx = -1 + (2 * (x + 0.5)) / size;
        const wz = -1 + (2 * (y + 0.5)) / size;
        const i = 4 * (y * size + x);
        const n = [normals[i]! / normals[i + 3]!, normals[i + 1]! / normals[i + 3]!, normals[i + 2]! / normals[i + 3]!];
        const inside = Math.max(Math.abs(wx), Math.abs(wz)) < 0.35;
        const outside = Math.max(Math.abs(wx), Math.abs(wz)) > 0.8;
        if (!inside && !outside) continue;
        const expected = inside ? expectedPatch : [0, 1, 0];
        for (let k = 0; k < 3; k++) assert.ok(Math.abs(n[k]! - expected[k]!) < 0.01, `pixel ${x},${y} normal ${n.map((v) => v.toFixed(3))} vs ${expected.map((v) => v.toFixed(3))}`);
        const luminance = radiance[i]! + radiance[i + 1]! + radiance[i + 2]!;
        if (inside) { patchLight += luminance; patchCount++; } else { outsideLight += luminance; outsideCount++; }
      }
    }
    assert.ok(patchCount > 50 && outsideCount > 50);
    const ratio = patchLight / patchCount / (outsideLight / outsideCount);
    assert.ok(ratio > 0.85 && ratio < 1.05, `the patch is lit like the flat plane (ratio ${ratio.toFixed(3)})`);
  } finally {
    renderer.destroy();
  }
});

test('updateScene renders what a new renderer renders, grows its buffers for more geometry, and refuses features its kernels lack', async () => {
  const device = await testDevice();
  const { document } = createBendingTube();
  const scene = await loadGltfScene(document, { camera: 'Front' });
  const options = { device, width: W, height: H, samplesPerPixel: 2, maxDepth: 2, toneMapping: 'linear' as const };
  const updated = await createWavefrontPathTracingComputeRenderer({ ...scene, ...options });
  try {
    const bent = await scene.pose({ time: 0.6 });
    // Two more tubes: the geometry buffers must grow.
    const instances = [...bent.instances, { mesh: 0, transform: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0.8, 0, 0, 1] }, { mesh: 0, transform: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -0.8, 0, 0, 1] }];
    await updated.renderFrame();
    const before = updated.getSnapshot();
    await updated.updateScene({ meshes: bent.meshes, instances });
    assert.equal(updated.getSnapshot().samplesAccumulated, 0, 'the accumulation restarts');
    await updated.renderFrame();
    const fresh = await createWavefrontPathTracingComputeRenderer({ ...scene, ...options, meshes: bent.meshes, instances });
    await fresh.renderFrame();
    const a = (await updated.readRadiance()).data;
    const b = (await fresh.readRadiance()).data;
    fresh.destroy();
    let worst = 0;
    for (let i = 0; i < a.length; i++) worst = Math.max(worst, Math.abs(a[i]! - b[i]!));
    assert.equal(worst, 0, 'the updated renderer and a new one give the same samples');
    assert.equal(updated.getSnapshot().triangleCount, 3 * before.triangleCount);

    // A plain material for the first renderer, an emissive override in the update: kernels specialised without emissive lights.
    // (The morphed plane's features: a uniform environment and AOVs.)
    const plain = await createWavefrontPathTracingComputeRenderer({ ...options, aovs: true, environment: { color: [1, 1, 1] }, materials: [{ baseColorFactor: [0.5, 0.5, 0.5, 1] }, { emissiveFactor: [1, 1, 1] }], meshes: [{ ...bent.meshes[0]!, material: 0 }], camera: scene.camera });
    await plain.renderFrame();
    const image = (await plain.readRadiance()).data;
    await assert.rejects(plain.updateScene({ instances: [{ mesh: 0, material: 1 }] }), (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_STATE' && e.field === 'instances' && /FEATURE_EMISSIVE_LIGHTS/.test(e.message));
    await assert.rejects(plain.updateScene({ meshes: [{ ...bent.meshes[0]!, material: 5 }] }), (e: unknown) => e instanceof GpuRendererError && e.field === 'meshes[0].material');
    assert.deepEqual(Array.from((await plain.readRadiance()).data), Array.from(image), 'a refused update leaves the renderer as it was');
    plain.destroy();
  } finally {
    updated.destroy();
  }
});

test('a sequence renderer moves poses of one topology (updateGeometry), replaces a variant\'s geometry (updateScene), and updateScene rebuilds on the GPU in gpu build mode', async () => {
  const device = await testDevice();
  const { document } = createBendingTube({ variants: true });
  const scene = await loadGltfScene(document, { camera: 'Front' });
  const { createSequenceRenderer } = await import('../../src/sequence/sequence-renderer.ts');
  const options = { device, width: W, height: H, samplesPerPixel: 2, maxDepth: 1, toneMapping: 'linear' as const };
  const sequence = createSequenceRenderer(options);
  try {
    await sequence.show({ ...scene });
    const moved = await scene.pose({ time: 0.7 });
    const renderer = await sequence.show({ ...moved });
    await renderer.renderFrame();
    const fresh = await createWavefrontPathTracingComputeRenderer({ ...moved, ...options });
    await fresh.renderFrame();
    assert.ok(iou(redMask((await renderer.readPixels()).data), redMask((await fresh.readPixels()).data)) > 0.99, 'the moved renderer shows the new pose');
    fresh.destroy();
    const blue = await moved.pose({ variant: 'Blue' });
    await sequence.show({ ...blue });
    assert.deepEqual(sequence.counts, { created: 1, moved: 1, replaced: 1 });
  } finally {
    sequence.destroy();
  }
  // updateScene in 'gpu' build mode: the new tree is built on the GPU; the image is the fresh renderer's.
  const bent = await scene.pose({ time: 0.4 });
  const instances = [...bent.instances, { mesh: 0, transform: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0.8, 0, 0, 1] }];
  const gpu = await createWavefrontPathTracingComputeRenderer({ ...scene, ...options, accelerationBuildMode: 'gpu' });
  await gpu.updateScene({ meshes: bent.meshes, instances });
  await gpu.renderFrame();
  const reference = await createWavefrontPathTracingComputeRenderer({ ...scene, ...options, meshes: bent.meshes, instances, accelerationBuildMode: 'gpu' });
  await reference.renderFrame();
  assert.deepEqual(Array.from((await gpu.readRadiance()).data), Array.from((await reference.readRadiance()).data));
  assert.equal(gpu.getSnapshot().bvhNodeCount, reference.getSnapshot().bvhNodeCount);
  gpu.destroy();
  reference.destroy();
});
