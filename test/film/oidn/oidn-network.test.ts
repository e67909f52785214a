// The WebGPU network (WGSL convolutions, autoexposure, input and output processing, tiles) against
// an independent CPU evaluation of the same weights (oidn-reference.ts: plain float64 loops), for
// both shipped weights, in f32 and (where the device has shader-f16) f16; and tiled against untiled.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { BufferUsage } from '../../../src/gpu/webgpu-constants.ts';
import { OidnNetwork } from '../../../src/film/denoise/oidn/oidn-network.ts';
import { denoiseOidnReference } from '../../../src/film/denoise/oidn/oidn-reference.ts';
import { planTensors, type OidnPrecision } from '../../../src/film/denoise/oidn/packing.ts';
import type { UNetModel } from '../../../src/film/denoise/oidn/unet.ts';
import { loadOidnModel } from '../../../src/film/denoise/oidn/weights.ts';
import { readBuffer, testDevice, uploadBuffer } from '../../helpers/gpu.ts';
import { testImages, type TestImages } from './images.ts';

async function gpuDenoise(model: UNetModel, precision: OidnPrecision, images: TestImages, maxMemoryBytes?: number, exactEmission = false): Promise<{ data: Float32Array; tiles: number }> {
  const device = await testDevice();
  const network = await OidnNetwork.create(device, model, { precision });
  const { width, height } = images;
  const output = device.createBuffer({ size: width * height * 16, usage: BufferUsage.STORAGE | BufferUsage.COPY_SRC });
  const source = {
    color: uploadBuffer(device, images.color),
    ...(model.inputChannels >= 6 ? { albedo: { buffer: uploadBuffer(device, images.albedo) } } : {}),
    ...(model.inputChannels >= 9 ? { normal: { buffer: uploadBuffer(device, images.normal) } } : {}),
    ...(exactEmission ? { emission: { buffer: uploadBuffer(device, images.emission) } } : {}),
  };
  const denoiser = network.createImageDenoiser(width, height, source, output, maxMemoryBytes === undefined ? {} : { maxMemoryBytes });
  try {
    const encoder = device.createCommandEncoder();
    denoiser.encode(encoder);
    device.queue.submit([encoder.finish()]);
    return { data: new Float32Array(await readBuffer(device, output)), tiles: denoiser.tiles.tiles.length };
  } finally {
    denoiser.destroy();
    network.destroy();
    output.destroy();
  }
}

function cpuDenoise(model: UNetModel, images: TestImages, exactEmission = false): Float32Array {
  const image = (data: Float32Array) => ({ width: images.width, height: images.height, data });
  return denoiseOidnReference(model, {
    color: image(images.color),
    ...(model.inputChannels >= 6 ? { albedo: image(images.albedo) } : {}),
    ...(model.inputChannels >= 9 ? { normal: image(images.normal) } : {}),
    ...(exactEmission ? { emission: image(images.emission) } : {}),
  });
}

/** Largest and mean |gpu - cpu| / (|cpu| + 0.01) over the colour channels; alpha must be 1. */
function agreement(gpu: Float32Array, cpu: Float32Array): { worst: number; mean: number } {
  let worst = 0, sum = 0, n = 0;
  for (let i = 0; i < gpu.length; i++) {
    if (i % 4 === 3) {
      assert.equal(gpu[i], 1);
      continue;
    }
    const e = Math.abs(gpu[i]! - cpu[i]!) / (Math.abs(cpu[i]!) + 0.01);
    worst = Math.max(worst, e);
    sum += e;
    n++;
  }
  return { worst, mean: sum / n };
}

test('f32: the WebGPU network equals the CPU evaluation of the same weights per pixel (colour + albedo + normal with the emission bypass, and colour only)', async () => {
  // 40x24: padded to 48x32, so the zero padding of the input is exercised.
  const images = testImages(40, 24, 7);
  for (const name of ['rt_hdr_alb_nrm', 'rt_hdr'] as const) {
    const model = await loadOidnModel(name);
    const exact = name === 'rt_hdr_alb_nrm';
    const cpu = cpuDenoise(model, images, exact);
    const gpu = await gpuDenoise(model, 'f32', images, undefined, exact);
    const { worst, mean } = agreement(gpu.data, cpu);
    // f32 storage and accumulation against float64: rounding only.
    assert.ok(worst < 1e-4, `${name}: worst relative difference ${worst}`);
    assert.ok(mean < 1e-5, `${name}: mean relative difference ${mean}`);
    // The network did something: the output is not the input.
    let changed = 0;
    for (let i = 0; i < cpu.length; i += 4) if (Math.abs(cpu[i]! - images.color[i]!) > 0.05 * (images.color[i]! + 0.1)) changed++;
    assert.ok(changed > cpu.length / 8, `${name}: ${changed} pixels changed`);
    if (exact) {
      // The emitter's pixels come back as its exact emission plus the network's (small) reflected part.
      const p = 4 * (8 * 40 + 14);
      assert.ok(gpu.data[p]! >= images.emission[p]! && gpu.data[p]! < images.emission[p]! + 10, `emitter pixel ${gpu.data[p]}`);
    }
  }
});

test('f16: the half-precision network agrees with the CPU evaluation within half-float tolerance', async (t) => {
  const device = await testDevice();
  if (!device.features.has('shader-f16')) {
    t.skip('the device has no shader-f16');
    return;
  }
  const images = testImages(32, 32, 3);
  const model = await loadOidnModel('rt_hdr_alb_nrm');
  const { worst, mean } = agreement((await gpuDenoise(model, 'f16', images)).data, cpuDenoise(model, images));
  // Activations and weights stored as binary16 (2^-11 relative) through 16 layers; 4-term dot
  // products in f16, sums in f32. Measured here: worst 0.6 %, mean 0.1 %.
  assert.ok(worst < 0.03, `worst relative difference ${worst}`);
  assert.ok(mean < 0.005, `mean relative difference ${mean}`);
  assert.ok(mean > 1e-5, 'f16 differs from f32 at all (it really ran in half precision)');
});

test('tiles: a budget that forces overlapping tiles gives the untiled result exactly', async () => {
  const images = testImages(288, 16, 5);
  const model = await loadOidnModel('rt_hdr_alb_nrm');
  const whole = await gpuDenoise(model, 'f32', images);
  // Room for 272x16 tiles only: the 288-pixel row takes overlapping tiles (96 pixels each side).
  const tiled = await gpuDenoise(model, 'f32', images, planTensors(model, 272, 16, 'f32').totalBytes);
  assert.equal(whole.tiles, 1);
  assert.ok(tiled.tiles > 1, `${tiled.tiles} tiles`);
  assert.deepEqual(tiled.data, whole.data);
});
