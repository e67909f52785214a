// The megakernel integrator against the wavefront: both run the same stage functions on the same
// random numbers, so they must compute the same samples. On lavapipe the images are bit-identical;
// a GPU compiler may contract floating-point operations differently in the two kernels, which can
// flip a rare path decision, so the check allows that: 99 % of the pixel values must agree to 1e-4
// (relative), and the mean per-pixel difference must be within 4 standard errors of 0 per channel.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { Document } from '@gltf-transform/core';
import { encode as encodePng } from 'fast-png';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/index.ts';
import { chooseIntegrator, integratorStorageBuffers } from '../../src/pathtracer/pipelines.ts';
import type { WavefrontFrameStats, WavefrontPathTracingOptions } from '../../src/pathtracer/types.ts';
import { createCornellBoxScene } from '../../src/scene/cornell-box.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { getGpu } from '../../src/gpu/acquire-device.ts';
import { testDevice } from '../helpers/gpu.ts';
import { quad, roundTrip } from './gltf-scenes.ts';
import { meanDifferenceZ } from '../helpers/image-stats.ts';

type Options = Omit<WavefrontPathTracingOptions, 'device' | 'integrator'>;

interface Render {
  stats: WavefrontFrameStats;
  radiance: Float32Array;
  albedo: Float32Array | null;
  normal: Float32Array | null;
}

async function render(options: Options, integrator: 'wavefront' | 'megakernel'): Promise<Render> {
  const device = await testDevice();
  const renderer = await createWavefrontPathTracingComputeRenderer({ device, ...options, integrator });
  try {
    assert.equal(renderer.getSnapshot().integrator, integrator);
    const stats = await renderer.renderFrame();
    assert.equal(stats.invalidSamples, 0);
    return {
      stats,
      radiance: (await renderer.readRadiance()).data,
      albedo: options.aovs ? (await renderer.readAov('albedo')).data : null,
      normal: options.aovs ? (await renderer.readAov('normal')).data : null,
    };
  } finally {
    renderer.destroy();
  }
}

/** Share of values of b within 1e-4 (relative, at least 1e-6 absolute) of a. */
function agreeingShare(a: Float32Array, b: Float32Array): number {
  assert.equal(a.length, b.length);
  let agree = 0;
  for (let i = 0; i < a.length; i++) if (Math.abs(a[i]! - b[i]!) <= Math.max(1e-6, 1e-4 * Math.abs(a[i]!))) agree++;
  return agree / a.length;
}

function assertSameImage(wave: Float32Array, mega: Float32Array, what: string): void {
  const share = agreeingShare(wave, mega);
  assert.ok(share >= 0.99, `${what}: ${(100 * share).toFixed(2)} % of values agree`);
  meanDifferenceZ(wave, mega, { identicalIsZero: true }).forEach((z, c) => assert.ok(Math.abs(z) < 4, `${what} channel ${c}: z = ${z}`));
}

function assertSameRays(wave: WavefrontFrameStats, mega: WavefrontFrameStats): void {
  assert.equal(mega.rays.camera, wave.rays.camera);
  for (const kind of ['extension', 'shadow'] as const) {
    assert.ok(Math.abs(mega.rays[kind] - wave.rays[kind]) <= 0.01 * wave.rays[kind], `${kind} rays: ${mega.rays[kind]} vs ${wave.rays[kind]}`);
  }
}

test('megakernel: the Cornell box (radiance, AOVs, ray counts) matches the wavefront for the same seed', async () => {
  const scene = createCornellBoxScene();
  const options: Options = {
    width: 24, height: 24, maxDepth: 8, samplesPerPixel: 4, seed: 11, aovs: true,
    meshes: scene.meshes, camera: scene.camera, ...(scene.environment ? { environment: scene.environment } : {}),
  };
  const wave = await render(options, 'wavefront');
  const mega = await render(options, 'megakernel');
  // Inside the closed box nearly every path bounces several times: the loop really ran.
  assert.ok(mega.stats.rays.extension > mega.stats.rays.camera && mega.stats.rays.shadow > 0.5 * mega.stats.rays.camera, JSON.stringify(mega.stats.rays));
  assertSameRays(wave.stats, mega.stats);
  assertSameImage(wave.radiance, mega.radiance, 'radiance');
  assertSameImage(wave.albedo!, mega.albedo!, 'albedo');
  assertSameImage(wave.normal!, mega.normal!, 'normal');
  let lum = 0;
  for (let i = 0; i < mega.radiance.length; i += 4) lum += mega.radiance[i]!;
  assert.ok(lum / (mega.radiance.length / 4) > 0.05, 'the image is not black');
});

/** A glTF scene: a checker-textured rough floor, a glossy metal panel and an emissive panel, in a dim environment. */
async function texturedScene(): Promise<Options> {
  const doc = new Document();
  const buffer = doc.createBuffer();
  const texels = new Uint8Array(4 * 4 * 4);
  for (let i = 0; i < 16; i++) texels.set(((i >> 2) + i) % 2 === 0 ? [230, 60, 40, 255] : [40, 120, 220, 255], 4 * i);
  const checker = doc.createTexture('checker').setMimeType('image/png').setImage(encodePng({ width: 4, height: 4, data: texels, channels: 4 }));
  const floor = doc.createMaterial('floor').setBaseColorTexture(checker).setMetallicFactor(0).setRoughnessFactor(0.8);
  const metal = doc.createMaterial('metal').setBaseColorFactor([0.9, 0.8, 0.6, 1]).setMetallicFactor(1).setRoughnessFactor(0.25);
  const lamp = doc.createMaterial('lamp').setBaseColorFactor([0, 0, 0, 1]).setEmissiveFactor([1, 1, 1]);
  const x = Math.SQRT1_2;
  const scene = doc.createScene().addChild(doc.createNode('floor').setMesh(quad(doc, buffer, floor, { x0: -2, y0: -2, x1: 2, y1: 2, normals: true })).setRotation([-x, 0, 0, x]))
    .addChild(doc.createNode('metal').setMesh(quad(doc, buffer, metal, { x0: -1, y0: 0, x1: 1, y1: 1.2, normals: true })).setTranslation([0, 0, -1]))
    .addChild(doc.createNode('lamp').setMesh(quad(doc, buffer, lamp, { x0: -0.6, y0: -0.6, x1: 0.6, y1: 0.6 })).setTranslation([0, 2.5, 0]).setRotation([x, 0, 0, x]));
  doc.getRoot().setDefaultScene(scene);
  const loaded = await roundTrip(doc);
  return {
    ...loaded, width: 24, height: 24, maxDepth: 5, samplesPerPixel: 4, seed: 5,
    camera: { position: [0, 1.5, 3.5], target: [0, 0.2, -0.5], up: [0, 1, 0], fovYDegrees: 45 }, environment: { color: [0.1, 0.12, 0.15] },
  };
}

test('megakernel: a textured glTF scene with adaptive sampling matches the wavefront for the same seed', async () => {
  const options = { ...(await texturedScene()), adaptiveThreshold: 0.05, minimumSamplesPerPixel: 4, samplesPerPixel: 8 };
  const wave = await render(options, 'wavefront');
  const mega = await render(options, 'megakernel');
  assert.ok(wave.stats.rays.shadow > 0 && wave.stats.rays.extension > 0);
  assertSameRays(wave.stats, mega.stats);
  assertSameImage(wave.radiance, mega.radiance, 'radiance');
});

test('integrator: an unknown form is a typed error naming the field', async () => {
  const device = await testDevice();
  await assert.rejects(
    createWavefrontPathTracingComputeRenderer({ device, width: 8, height: 8, integrator: 'persistent' as 'megakernel' }),
    (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_OPTION' && e.field === 'integrator' && /wavefront/.test(e.message),
  );
});

test('integrator: on a device of the default 8 storage buffers per stage, a megakernel request runs the wavefront, says so, and renders its image', async () => {
  const adapter = await (await getGpu())!.requestAdapter();
  // WebGPU's default limits (no limit raised): 8 storage buffers per shader stage, fewer than the
  // megakernel binds and what many browser adapters expose.
  const device = await adapter!.requestDevice();
  assert.equal(device.limits.maxStorageBuffersPerShaderStage, 8);
  const scene = createCornellBoxScene();
  const options = { device, width: 12, height: 12, maxDepth: 4, samplesPerPixel: 2, seed: 3, meshes: scene.meshes, camera: scene.camera };
  const images: Float32Array[] = [];
  try {
    for (const integrator of ['megakernel', 'wavefront'] as const) {
      const renderer = await createWavefrontPathTracingComputeRenderer({ ...options, integrator });
      try {
        const snapshot = renderer.getSnapshot();
        assert.equal(snapshot.integrator, 'wavefront');
        assert.equal(snapshot.requestedIntegrator, integrator);
        const said = snapshot.warnings.filter((w) => /megakernel/.test(w));
        if (integrator === 'megakernel') {
          assert.equal(said.length, 1, JSON.stringify(snapshot.warnings));
          assert.match(said[0]!, /binds 13 storage buffers.*offers 8 per shader stage.*wavefront/);
        } else {
          assert.deepEqual(said, []);
        }
        const stats = await renderer.renderFrame();
        assert.equal(stats.invalidSamples, 0);
        assert.ok(stats.rays.extension > 0);
        images.push((await renderer.readRadiance()).data);
      } finally {
        renderer.destroy();
      }
    }
  } finally {
    device.destroy();
  }
  // The same kernels on the same device and seed: the same image, bit for bit, and not black.
  assert.deepEqual(images[0], images[1]);
  assert.ok(images[0]!.some((v, i) => i % 4 !== 3 && v > 0));
});

test('integrator: the wavefront binds at most WebGPU\'s guaranteed 8 storage buffers per stage, so it is the fallback that always runs', () => {
  // The counts come from the bindings that survive linking (programs.generated.ts), per kernel.
  assert.ok(integratorStorageBuffers('wavefront') <= 8, `the wavefront binds ${integratorStorageBuffers('wavefront')}`);
  assert.ok(integratorStorageBuffers('megakernel') > 8);
  const limits = (maxStorageBuffersPerShaderStage: number) => ({ maxStorageBuffersPerShaderStage }) as GPUSupportedLimits;
  assert.deepEqual(chooseIntegrator('megakernel', limits(16)), { integrator: 'megakernel', warning: null });
  assert.deepEqual(chooseIntegrator('wavefront', limits(8)), { integrator: 'wavefront', warning: null });
  assert.equal(chooseIntegrator('megakernel', limits(integratorStorageBuffers('megakernel') - 1)).integrator, 'wavefront');
  // Below the WebGPU minimum nothing runs: a typed error naming the field.
  assert.throws(
    () => chooseIntegrator('megakernel', limits(7)),
    (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_OPTION' && e.field === 'integrator' && /offers 7 per shader stage/.test(e.message),
  );
});
