/**
 * Per-material GPU state: the RasterMaterial uniform, the KHR_texture_transform rows of every slot
 * and the bind group of its 13 texture slots (unbound slots get a 1 x 1 fallback the shader never
 * reads: the texture mask says which are bound).
 */
import { allocateStructArray, writeStruct } from '../../gpu-layout/struct-layout.ts';
import { BufferUsage } from '../../gpu/webgpu-constants.ts';
import type { RasterMaterial } from '../scene/raster-material.ts';
import { rasterConstants, rasterMaterialLayout, rasterTextureSlots } from './raster-layout.ts';
import type { RasterTextures } from './textures.ts';

const alphaModes = { OPAQUE: rasterConstants.ALPHA_OPAQUE, MASK: rasterConstants.ALPHA_MASK, BLEND: rasterConstants.ALPHA_BLEND } as const;

/** The material uniform's bytes and the transform rows. */
export function packRasterMaterial(m: RasterMaterial): { uniform: ArrayBuffer; transforms: Float32Array } {
  const uniform = allocateStructArray(rasterMaterialLayout, 1);
  const transforms = new Float32Array(8 * rasterTextureSlots.length);
  let textureMask = 0;
  let texCoordMask = 0;
  rasterTextureSlots.forEach((slot, i) => {
    const ref = m.textures[slot.name];
    const rows = ref?.transform ?? { transform0: [1, 0, 0], transform1: [0, 1, 0] };
    transforms.set(rows.transform0, 8 * i);
    transforms.set(rows.transform1, 8 * i + 4);
    if (ref === undefined) return;
    textureMask |= 1 << i;
    if (ref.texCoord === 1) texCoordMask |= 1 << i;
  });
  const c = m.core;
  writeStruct(rasterMaterialLayout, new DataView(uniform), 0, {
    baseColor: c.baseColor,
    emissive: c.emission,
    metallic: c.metallic,
    roughness: c.roughness,
    ior: c.ior,
    alphaCutoff: c.alphaCutoff,
    alphaMode: alphaModes[c.alphaMode],
    normalScale: m.textures.normalTexture?.scale ?? 1,
    occlusionStrength: m.textures.occlusionTexture?.scale ?? 1,
    clearcoat: m.clearcoat,
    clearcoatRoughness: m.clearcoatRoughness,
    sheenColor: m.sheenColor,
    sheenRoughness: m.sheenRoughness,
    specularColor: m.specularColor,
    specular: m.specular,
    attenuationColor: m.attenuationColor,
    transmission: m.transmission,
    clearcoatNormalScale: m.textures.clearcoatNormalTexture?.scale ?? 1,
    thickness: m.thickness,
    attenuationDistance: Number.isFinite(m.attenuationDistance) ? m.attenuationDistance : 0,
    textureMask,
    texCoordMask,
    doubleSided: c.doubleSided ? 1 : 0,
  });
  return { uniform, transforms };
}

export interface GpuRasterMaterial {
  readonly bindGroup: GPUBindGroup;
  readonly blend: boolean;
  readonly doubleSided: boolean;
  destroy(): void;
}

export function createGpuMaterial(device: GPUDevice, layout: GPUBindGroupLayout, m: RasterMaterial, textures: RasterTextures): GpuRasterMaterial {
  const packed = packRasterMaterial(m);
  const uniform = device.createBuffer({ label: 'raster material', size: packed.uniform.byteLength, usage: BufferUsage.UNIFORM | BufferUsage.COPY_DST });
  device.queue.writeBuffer(uniform, 0, packed.uniform);
  const transforms = device.createBuffer({ label: 'raster texture transforms', size: packed.transforms.byteLength, usage: BufferUsage.UNIFORM | BufferUsage.COPY_DST });
  device.queue.writeBuffer(transforms, 0, packed.transforms);
  const n = rasterTextureSlots.length;
  const entries: GPUBindGroupEntry[] = [
    { binding: 0, resource: { buffer: uniform } },
    { binding: 1, resource: { buffer: transforms } },
  ];
  rasterTextureSlots.forEach((slot, i) => {
    const ref = m.textures[slot.name];
    entries.push({ binding: 2 + i, resource: ref === undefined ? textures.fallbackView : textures.view(ref.texture, slot.srgb) });
    entries.push({ binding: 2 + n + i, resource: ref === undefined ? textures.fallbackSampler : textures.sampler(ref.texture) });
  });
  const bindGroup = device.createBindGroup({ label: 'raster material', layout, entries });
  return {
    bindGroup,
    blend: m.core.alphaMode === 'BLEND',
    doubleSided: m.core.doubleSided,
    destroy() {
      uniform.destroy();
      transforms.destroy();
    },
  };
}
