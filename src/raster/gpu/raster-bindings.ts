/**
 * Every resource binding of the raster programs, by binding set (programs that share bind group
 * layouts): `draw` (forward shading, shadow and background passes), `skin` (the skinning compute
 * pass), `ibl` (environment precomputation) and `resolve` (tone mapping to the output). The WGSL
 * declarations (`package::raster::generated_layout`) and the bind group layouts are both generated
 * from this table.
 */
import type { BindingSpec } from '../../gpu-layout/bindings.ts';
import { ShaderStage } from '../../gpu/webgpu-constants.ts';
import { rasterTextureSlots } from './raster-layout.ts';

export type RasterBindingSet = 'draw' | 'skin' | 'ibl' | 'resolve';

/** A raster binding: a binding table entry with the set it belongs to and its stages. */
export type RasterBindingSpec = BindingSpec & { set: RasterBindingSet; visibility: number };

const VF = ShaderStage.VERTEX | ShaderStage.FRAGMENT;
const F = ShaderStage.FRAGMENT;
const C = ShaderStage.COMPUTE;

const materialTextures: Record<string, RasterBindingSpec> = {};
rasterTextureSlots.forEach((slot, i) => {
  materialTextures[slot.name] = { set: 'draw', group: 1, binding: 2 + i, visibility: F, kind: 'texture', type: 'texture_2d<f32>', sampleType: 'float', doc: `material ${slot.name}` };
  materialTextures[`${slot.name}Sampler`] = { set: 'draw', group: 1, binding: 2 + rasterTextureSlots.length + i, visibility: F, kind: 'sampler', doc: `glTF sampler of ${slot.name}` };
});

export const rasterBindings: Record<string, RasterBindingSpec> = {
  // draw, group 0: per frame.
  frame: { set: 'draw', group: 0, binding: 0, visibility: VF, kind: 'uniform', type: 'RasterFrame', doc: 'camera, environment, lights, shadow' },
  lights: { set: 'draw', group: 0, binding: 1, visibility: F, kind: 'storage', access: 'read', type: 'array<PunctualLight>', doc: 'KHR_lights_punctual lights (and the sun)' },
  shadowMap: { set: 'draw', group: 0, binding: 2, visibility: F, kind: 'texture', type: 'texture_depth_2d', sampleType: 'depth', doc: 'depth from the shadow-casting light' },
  shadowSampler: { set: 'draw', group: 0, binding: 3, visibility: F, kind: 'sampler', comparison: true, doc: 'PCF comparison sampler' },
  specularMap: { set: 'draw', group: 0, binding: 4, visibility: F, kind: 'texture', type: 'texture_2d<f32>', sampleType: 'float', doc: 'prefiltered specular radiance (equirect, one roughness per mip level)' },
  environmentSampler: { set: 'draw', group: 0, binding: 5, visibility: F, kind: 'sampler', doc: 'trilinear, repeat in u, clamp in v' },
  brdfLut: { set: 'draw', group: 0, binding: 6, visibility: F, kind: 'texture', type: 'texture_2d<f32>', sampleType: 'float', doc: 'split-sum GGX scale and bias (rg) and sheen albedo (b) by (NdotV, roughness)' },
  lutSampler: { set: 'draw', group: 0, binding: 7, visibility: F, kind: 'sampler', doc: 'bilinear, clamp' },
  irradianceSh: { set: 'draw', group: 0, binding: 8, visibility: F, kind: 'storage', access: 'read', type: 'array<vec4f, 9>', doc: 'order-2 spherical harmonics of the cosine-convolved environment / pi' },
  // draw, group 1: per material.
  material: { set: 'draw', group: 1, binding: 0, visibility: F, kind: 'uniform', type: 'RasterMaterial', doc: 'material factors and texture masks' },
  textureTransforms: { set: 'draw', group: 1, binding: 1, visibility: F, kind: 'uniform', type: `array<vec4f, ${2 * rasterTextureSlots.length}>`, doc: 'KHR_texture_transform rows per texture slot (two vec4 per slot)' },
  ...materialTextures,
  // draw, group 2: per draw.
  draw: { set: 'draw', group: 2, binding: 0, visibility: VF, kind: 'uniform', dynamic: true, type: 'RasterDraw', doc: 'model matrix and stream flags' },
  // skin, group 0.
  skinParams: { set: 'skin', group: 0, binding: 0, visibility: C, kind: 'uniform', dynamic: true, type: 'RasterSkinParams', doc: 'one skinned primitive' },
  skinSource: { set: 'skin', group: 0, binding: 1, visibility: C, kind: 'storage', access: 'read', type: 'array<f32>', doc: 'bind-pose streams and morph target deltas' },
  skinInfluences: { set: 'skin', group: 0, binding: 2, visibility: C, kind: 'storage', access: 'read', type: 'array<u32>', doc: 'joint indices then weights (bit-cast f32)' },
  jointMatrices: { set: 'skin', group: 0, binding: 3, visibility: C, kind: 'storage', access: 'read', type: 'array<mat4x4f>', doc: 'joint matrices (world(joint) x inverse bind) per skin' },
  morphWeights: { set: 'skin', group: 0, binding: 4, visibility: C, kind: 'storage', access: 'read', type: 'array<f32>', doc: 'morph target weights per drawable' },
  skinOutput: { set: 'skin', group: 0, binding: 5, visibility: C, kind: 'storage', access: 'read_write', type: 'array<f32>', doc: 'skinned positions, normals and tangents (vertex buffers)' },
  // ibl, group 0.
  iblParams: { set: 'ibl', group: 0, binding: 0, visibility: C, kind: 'uniform', dynamic: true, type: 'RasterIblParams', doc: 'sizes and roughness of one pass' },
  iblSource: { set: 'ibl', group: 0, binding: 1, visibility: C, kind: 'texture', type: 'texture_2d<f32>', sampleType: 'float', doc: 'source radiance (equirect with mips)' },
  iblSampler: { set: 'ibl', group: 0, binding: 2, visibility: C, kind: 'sampler', doc: 'trilinear, repeat in u, clamp in v' },
  iblOutput: { set: 'ibl', group: 0, binding: 3, visibility: C, kind: 'storageTexture', format: 'rgba16float', doc: 'the level being written' },
  iblSh: { set: 'ibl', group: 0, binding: 4, visibility: C, kind: 'storage', access: 'read_write', type: 'array<vec4f, 9>', doc: 'irradiance spherical harmonics' },
  // resolve, group 0.
  resolveFrame: { set: 'resolve', group: 0, binding: 0, visibility: F, kind: 'uniform', type: 'RasterFrame', doc: 'exposure, tone mapping, output encoding' },
  hdrColor: { set: 'resolve', group: 0, binding: 1, visibility: F, kind: 'texture', type: 'texture_2d<f32>', sampleType: 'unfilterable-float', doc: 'resolved linear radiance' },
};

/**
 * Every binding of a set: the programs of a set share their bind group layouts (the draw passes
 * bind one set of groups to the forward, shadow and background pipelines), so the layouts hold
 * the set's whole table rather than one program's reflected bindings.
 */
export function rasterSetBindings(set: RasterBindingSet): string[] {
  return Object.entries(rasterBindings)
    .filter(([, s]) => s.set === set)
    .map(([name]) => name);
}
