/**
 * Image-based lighting, computed on the GPU at load: the environment's equirect map (from
 * `environmentMap` or a procedural sky) uploaded as half floats with a solid-angle-weighted mip
 * chain, a prefiltered specular chain (one GGX roughness per level), order-2 spherical harmonics of
 * the irradiance, and the split-sum BRDF lookup table. A uniform or black environment needs none of
 * the maps: the forward pass evaluates it exactly.
 */
import { float32ToHalfBits } from '../../math/half-float.ts';
import type { EnvironmentMap } from '../../lighting/environment-map.ts';
import { allocateStructArray, writeStruct } from '../../gpu-layout/struct-layout.ts';
import { BufferUsage, TextureUsage } from '../../gpu/webgpu-constants.ts';
import { HDR_FORMAT, type RasterPipelines } from './pipelines.ts';
import { rasterConstants, rasterIblParamsLayout } from './raster-layout.ts';

export const BRDF_LUT_SIZE = 64;
const LUT_SAMPLES = 512;
const PREFILTER_SAMPLES = 128;
/** Largest width of the prefiltered chain's level 0 (roughness 0). */
const MAX_SPECULAR_WIDTH = 512;
/** Coarsest level of the specular chain: 8 x 4 texels. */
const MIN_SPECULAR_WIDTH = 8;
const SH_MAX_WIDTH = 128;
const PARAMS_STRIDE = 256;

export interface RasterEnvironment {
  readonly mode: number;
  readonly specularView: GPUTextureView;
  readonly specularMipCount: number;
  readonly irradianceSh: GPUBuffer;
  /** Radiance above half-float range had to be stored as 65504. */
  readonly saturatedTexels: number;
  readonly bytes: number;
  destroy(): void;
}

function levelCount(width: number, minWidth: number): number {
  let n = 1;
  while (width >> n >= minWidth && width >> n >= 1) n++;
  return n;
}

/** Packs IBL parameter blocks at 256-byte strides (dynamic uniform offsets). */
function paramsBuffer(device: GPUDevice, blocks: Record<string, number | number[]>[]): GPUBuffer {
  const bytes = new ArrayBuffer(Math.max(1, blocks.length) * PARAMS_STRIDE);
  const one = allocateStructArray(rasterIblParamsLayout, 1);
  blocks.forEach((b, i) => {
    writeStruct(rasterIblParamsLayout, new DataView(one), 0, { outputSize: [0, 0], sourceSize: [0, 0], roughness: 0, sampleCount: 0, sourceMipCount: 1, level: 0, ...b });
    new Uint8Array(bytes, i * PARAMS_STRIDE, one.byteLength).set(new Uint8Array(one));
  });
  const buffer = device.createBuffer({ label: 'raster ibl params', size: bytes.byteLength, usage: BufferUsage.UNIFORM | BufferUsage.COPY_DST });
  device.queue.writeBuffer(buffer, 0, bytes);
  return buffer;
}

function paramsEntry(buffer: GPUBuffer): GPUBindGroupEntry {
  return { binding: 0, resource: { buffer, size: rasterIblParamsLayout.size } };
}

/** The split-sum lookup table (rg: GGX scale and bias, b: sheen albedo), once per renderer. */
export function computeBrdfLut(device: GPUDevice, pipelines: RasterPipelines, dummySh: GPUBuffer): GPUTexture {
  const lut = device.createTexture({ label: 'raster brdf lut', size: { width: BRDF_LUT_SIZE, height: BRDF_LUT_SIZE }, format: HDR_FORMAT, usage: TextureUsage.TEXTURE_BINDING | TextureUsage.STORAGE_BINDING });
  const scratch = device.createTexture({ size: { width: 1, height: 1 }, format: HDR_FORMAT, usage: TextureUsage.TEXTURE_BINDING });
  const params = paramsBuffer(device, [{ outputSize: [BRDF_LUT_SIZE, BRDF_LUT_SIZE], sampleCount: LUT_SAMPLES }]);
  const bindGroup = device.createBindGroup({
    layout: pipelines.iblLayout,
    entries: [paramsEntry(params), { binding: 1, resource: scratch.createView() }, { binding: 2, resource: device.createSampler({}) }, { binding: 3, resource: lut.createView() }, { binding: 4, resource: { buffer: dummySh } }],
  });
  const encoder = device.createCommandEncoder({ label: 'raster brdf lut' });
  const pass = encoder.beginComputePass();
  pass.setPipeline(pipelines.compute('brdfLut'));
  pass.setBindGroup(0, bindGroup, [0]);
  const groups = Math.ceil(BRDF_LUT_SIZE / rasterConstants.IBL_WORKGROUP_SIZE);
  pass.dispatchWorkgroups(groups, groups);
  pass.end();
  device.queue.submit([encoder.finish()]);
  void device.queue.onSubmittedWorkDone().then(() => {
    params.destroy();
    scratch.destroy();
  });
  return lut;
}

function halfFloatTexels(map: EnvironmentMap): { data: Uint16Array; saturated: number } {
  const data = new Uint16Array(map.data.length);
  let saturated = 0;
  for (let i = 0; i < map.data.length; i++) {
    let v = map.data[i]!;
    if (v > 65504) {
      v = 65504;
      saturated++;
    }
    data[i] = float32ToHalfBits(v);
  }
  return { data, saturated };
}

/** Uniform or black environments: 1 x 1 placeholder maps the shader never reads. */
export function createConstantEnvironment(device: GPUDevice, mode: number): RasterEnvironment {
  const texture = device.createTexture({ label: 'raster environment placeholder', size: { width: 1, height: 1 }, format: HDR_FORMAT, usage: TextureUsage.TEXTURE_BINDING });
  const irradianceSh = device.createBuffer({ label: 'raster irradiance sh', size: 9 * 16, usage: BufferUsage.STORAGE });
  return {
    mode,
    specularView: texture.createView(),
    specularMipCount: 1,
    irradianceSh,
    saturatedTexels: 0,
    bytes: 8 + 9 * 16,
    destroy() {
      texture.destroy();
      irradianceSh.destroy();
    },
  };
}

/** Prefilters an equirect environment map on the GPU. */
export function createMapEnvironment(device: GPUDevice, pipelines: RasterPipelines, map: EnvironmentMap, options: { prefilterSamples?: number } = {}): RasterEnvironment {
  const { width, height } = map;
  const sourceLevels = levelCount(Math.min(width, height * 2), 2);
  const source = device.createTexture({
    label: 'raster environment source',
    size: { width, height },
    mipLevelCount: sourceLevels,
    format: HDR_FORMAT,
    usage: TextureUsage.TEXTURE_BINDING | TextureUsage.STORAGE_BINDING | TextureUsage.COPY_DST,
  });
  const half = halfFloatTexels(map);
  device.queue.writeTexture({ texture: source }, half.data, { bytesPerRow: 8 * width, rowsPerImage: height }, { width, height });
  const specularWidth = Math.max(MIN_SPECULAR_WIDTH, Math.min(MAX_SPECULAR_WIDTH, width));
  const specularLevels = levelCount(specularWidth, MIN_SPECULAR_WIDTH);
  const specular = device.createTexture({
    label: 'raster prefiltered specular',
    size: { width: specularWidth, height: Math.max(1, specularWidth >> 1) },
    mipLevelCount: specularLevels,
    format: HDR_FORMAT,
    usage: TextureUsage.TEXTURE_BINDING | TextureUsage.STORAGE_BINDING,
  });
  const irradianceSh = device.createBuffer({ label: 'raster irradiance sh', size: 9 * 16, usage: BufferUsage.STORAGE });
  const size = (level: number): [number, number] => [Math.max(1, width >> level), Math.max(1, height >> level)];
  let shLevel = 0;
  while (size(shLevel)[0] > SH_MAX_WIDTH && shLevel + 1 < sourceLevels) shLevel++;
  const blocks: Record<string, number | number[]>[] = [];
  for (let k = 1; k < sourceLevels; k++) blocks.push({ outputSize: size(k), sourceSize: size(k - 1), level: 0 });
  const prefilterBase = blocks.length;
  const samples = options.prefilterSamples ?? PREFILTER_SAMPLES;
  for (let k = 0; k < specularLevels; k++) {
    blocks.push({ outputSize: [Math.max(1, specularWidth >> k), Math.max(1, specularWidth >> (k + 1))], sourceSize: [width, height], roughness: specularLevels === 1 ? 0 : k / (specularLevels - 1), sampleCount: samples, sourceMipCount: sourceLevels });
  }
  blocks.push({ sourceSize: size(shLevel), level: shLevel });
  const params = paramsBuffer(device, blocks);
  const sampler = device.createSampler({ addressModeU: 'repeat', addressModeV: 'clamp-to-edge', magFilter: 'linear', minFilter: 'linear', mipmapFilter: 'linear' });
  const dummyOut = device.createTexture({ size: { width: 1, height: 1 }, format: HDR_FORMAT, usage: TextureUsage.STORAGE_BINDING });
  const bind = (sourceView: GPUTextureView, output: GPUTextureView): GPUBindGroup =>
    device.createBindGroup({
      layout: pipelines.iblLayout,
      entries: [paramsEntry(params), { binding: 1, resource: sourceView }, { binding: 2, resource: sampler }, { binding: 3, resource: output }, { binding: 4, resource: { buffer: irradianceSh } }],
    });
  const encoder = device.createCommandEncoder({ label: 'raster environment prefilter' });
  const pass = encoder.beginComputePass();
  const wg = rasterConstants.IBL_WORKGROUP_SIZE;
  pass.setPipeline(pipelines.compute('iblDownsample'));
  for (let k = 1; k < sourceLevels; k++) {
    pass.setBindGroup(0, bind(source.createView({ baseMipLevel: k - 1, mipLevelCount: 1 }), source.createView({ baseMipLevel: k, mipLevelCount: 1 })), [(k - 1) * PARAMS_STRIDE]);
    const [w, h] = size(k);
    pass.dispatchWorkgroups(Math.ceil(w / wg), Math.ceil(h / wg));
  }
  pass.setPipeline(pipelines.compute('iblPrefilter'));
  const sourceView = source.createView();
  for (let k = 0; k < specularLevels; k++) {
    pass.setBindGroup(0, bind(sourceView, specular.createView({ baseMipLevel: k, mipLevelCount: 1 })), [(prefilterBase + k) * PARAMS_STRIDE]);
    pass.dispatchWorkgroups(Math.ceil(Math.max(1, specularWidth >> k) / wg), Math.ceil(Math.max(1, specularWidth >> (k + 1)) / wg));
  }
  pass.setPipeline(pipelines.compute('iblIrradiance'));
  pass.setBindGroup(0, bind(sourceView, dummyOut.createView()), [(blocks.length - 1) * PARAMS_STRIDE]);
  pass.dispatchWorkgroups(1);
  pass.end();
  device.queue.submit([encoder.finish()]);
  void device.queue.onSubmittedWorkDone().then(() => {
    params.destroy();
    dummyOut.destroy();
    source.destroy();
  });
  let bytes = 9 * 16;
  for (let k = 0; k < specularLevels; k++) bytes += 8 * Math.max(1, specularWidth >> k) * Math.max(1, specularWidth >> (k + 1));
  return {
    mode: rasterConstants.ENVIRONMENT_MAP,
    specularView: specular.createView(),
    specularMipCount: specularLevels,
    irradianceSh,
    saturatedTexels: half.saturated,
    bytes,
    destroy() {
      specular.destroy();
      irradianceSh.destroy();
    },
  };
}
