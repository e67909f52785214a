// AOVs against analytic scenes: object and material ids of the first non-specular hit (instances,
// shared materials, analytic shapes, background -1), emission and coverage; the variance AOV against
// a CPU estimate from the same samples; sample counts; bad names and states as typed errors.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { testDevice } from '../helpers/gpu.ts';
import { cornellRenderer, lambert, luminance, perSampleRadiance, rect, squareCamera } from '../pathtracer/output-helpers.ts';

const SIZE = 16;

test('object and material ids, emission and coverage of the first non-specular hit', async () => {
  const device = await testDevice();
  const quad = rect(-1, -1, 1, 1, 0);
  // Left quarter: sky. Then instance id 7 (material 1), instance without id (its index, material 0),
  // and an analytic box (its own material, numbered after the scene's) in the right quarter.
  const renderer = await createWavefrontPathTracingComputeRenderer({
    device, width: SIZE, height: SIZE, samplesPerPixel: 4, camera: squareCamera, aovs: true, environment: { color: [0.5, 0.5, 0.5] },
    materials: [lambert([0.8, 0.2, 0.2]), { baseColorFactor: [0, 0, 0, 1], emissiveFactor: [2, 1, 0.5], emissiveStrength: 1, metallicFactor: 0, roughnessFactor: 1 }],
    meshes: [quad],
    instances: [
      { mesh: 0, id: 7, material: 1, transform: [0.25, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -0.25, 0, 0, 1] },
      { mesh: 0, transform: [0.25, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0.25, 0, 0, 1] },
    ],
    sceneObjects: [{ type: 'box', min: [0.5, -1, -0.5], max: [1, 1, 0], color: [0.1, 0.6, 0.2], roughness: 1, metallic: 0 }],
  });
  try {
    await renderer.renderFrame();
    const object = (await renderer.readAov('objectId')).data;
    const material = (await renderer.readAov('materialId')).data;
    const emission = (await renderer.readAov('emission')).data;
    const albedo = (await renderer.readAov('albedo')).data;
    const expected = [
      { object: -1, material: -1, emission: [0, 0, 0], coverage: 0 },
      { object: 7, material: 1, emission: [2, 1, 0.5], coverage: 1 },
      { object: 1, material: 0, emission: [0, 0, 0], coverage: 1 },
      { object: 2, material: 2, emission: [0, 0, 0], coverage: 1 },
    ];
    for (let y = 0; y < SIZE; y++) {
      for (let x = 0; x < SIZE; x++) {
        // Pixel columns 1-2 of each quarter: away from the boundaries the jitter can cross.
        if (x % 4 === 0 || x % 4 === 3) continue;
        const e = expected[Math.floor(x / 4)]!;
        const p = 4 * (y * SIZE + x);
        assert.equal(object[p], e.object, `object id at (${x}, ${y})`);
        assert.equal(material[p], e.material, `material id at (${x}, ${y})`);
        e.emission.forEach((v, c) => assert.ok(Math.abs(emission[p + c]! - v) < 1e-6, `emission at (${x}, ${y})`));
        assert.equal(emission[p + 3], e.coverage);
        assert.equal(albedo[p + 3], e.coverage);
      }
    }
  } finally {
    renderer.destroy();
  }
});

test('the variance AOV equals the CPU estimate from the same samples; sample counts', async () => {
  const n = 5;
  const renderer = await cornellRenderer(SIZE, { seed: 12, aovs: true });
  try {
    const samples = await perSampleRadiance(renderer, n);
    const emission = (await renderer.readAov('emission')).data;
    const variance = (await renderer.readAov('variance')).data;
    const counts = (await renderer.readAov('sampleCount')).data;
    for (let p = 0; p < SIZE * SIZE; p++) {
      assert.equal(counts[4 * p], n);
      for (let c = 0; c < 3; c++) {
        const values = samples.map((s) => s[3 * p + c]!);
        const mean = values.reduce((a, b) => a + b, 0) / n;
        const cpu = values.reduce((a, v) => a + (v - mean) ** 2, 0) / (n - 1) / n;
        assert.ok(Math.abs(variance[4 * p + c]! - cpu) <= 1e-3 * cpu + 1e-6 * mean * mean + 1e-9, `pixel ${p} channel ${c}: GPU ${variance[4 * p + c]} CPU ${cpu}`);
      }
      // Where every sample sees the same emission (none, or the light's), the alpha channel is the
      // luminance variance of (radiance - emission) over the same samples.
      const constant = emission[4 * p + 3] === 1 && (emission[4 * p] === 0 || emission[4 * p]! >= 17 - 1e-4);
      if (constant) {
        const ys = samples.map((s) => luminance(s[3 * p]!, s[3 * p + 1]!, s[3 * p + 2]!) - luminance(emission[4 * p]!, emission[4 * p + 1]!, emission[4 * p + 2]!));
        const my = ys.reduce((a, b) => a + b, 0) / n;
        const cpu = ys.reduce((a, v) => a + (v - my) ** 2, 0) / (n - 1) / n;
        assert.ok(Math.abs(variance[4 * p + 3]! - cpu) <= 2e-3 * cpu + 1e-5 * my * my + 1e-9, `pixel ${p} luminance: GPU ${variance[4 * p + 3]} CPU ${cpu}`);
      }
    }
  } finally {
    renderer.destroy();
  }
  // Below two samples the variance is unknown.
  const single = await cornellRenderer(4, { aovs: true });
  try {
    await single.renderFrame({ samplesPerPixel: 1 });
    assert.ok((await single.readAov('variance')).data.every((v) => v === Infinity));
  } finally {
    single.destroy();
  }
});

test('unknown AOV names and AOVs that were not enabled are typed errors', async () => {
  const device = await testDevice();
  const off = await createWavefrontPathTracingComputeRenderer({ device, width: 4, height: 4 });
  try {
    await off.renderFrame();
    await assert.rejects(off.readAov('albedo'), (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_STATE' && e.field === 'aovs');
    await assert.rejects(off.readAov('beauty' as never), (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_OPTION' && e.field === 'name');
    // The sample count needs no AOV accumulation.
    assert.ok((await off.readAov('sampleCount')).data.every((v, i) => (i % 4 === 0 ? v === 1 : true)));
  } finally {
    off.destroy();
  }
});
