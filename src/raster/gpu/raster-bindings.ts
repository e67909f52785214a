/**
 * Every resource binding of the raster programs, by binding set (programs that share bind group
 * layouts): `draw` (forward shading, shadow and background passes), `skin` (the skinning compute
 * pass), `ibl` (environment precomputation) and `resolve` (tone mapping to the output). The WGSL
 * declarations (`package::raster::generated_layout`) and the bind group layouts are both generated
 * from this table.
 */
import { ShaderStage } from '../../gpu/webgpu-constants.ts';
import { rasterTextureSlots } from './raster-layout.ts';

export type RasterBindingSet = 'draw' | 'skin' | 'ibl' | 'resolve';

type Resource =
  | { kind: 'uniform'; type: string; dynamic?: boolean }
  | { kind: 'storage'; type: string; access: 'read' | 'read_write' }
  | { kind: 'texture'; type: string; sampleType: GPUTextureSampleType }
  | { kind: 'sampler'; comparison?: boolean }
  | { kind: 'storageTexture'; format: GPUTextureFormat };

export type RasterBindingSpec = { set: RasterBindingSet; group: number; binding: number; visibility: number; doc: string } & Resource;

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

/** The WGSL declaration of one binding. */
export function rasterBindingDeclaration(name: string, spec: RasterBindingSpec): string {
  const at = `@group(${spec.group}) @binding(${spec.binding})`;
  const comment = `// ${spec.doc}`;
  switch (spec.kind) {
    case 'uniform':
      return `${comment}\n${at} var<uniform> ${name}: ${spec.type};`;
    case 'storage':
      return `${comment}\n${at} var<storage, ${spec.access}> ${name}: ${spec.type};`;
    case 'texture':
      return `${comment}\n${at} var ${name}: ${spec.type};`;
    case 'sampler':
      return `${comment}\n${at} var ${name}: ${spec.comparison ? 'sampler_comparison' : 'sampler'};`;
    case 'storageTexture':
      return `${comment}\n${at} var ${name}: texture_storage_2d<${spec.format}, write>;`;
  }
}

function layoutEntry(spec: RasterBindingSpec): GPUBindGroupLayoutEntry {
  const base = { binding: spec.binding, visibility: spec.visibility };
  switch (spec.kind) {
    case 'uniform':
      return { ...base, buffer: { type: 'uniform', hasDynamicOffset: spec.dynamic === true } };
    case 'storage':
      return { ...base, buffer: { type: spec.access === 'read' ? 'read-only-storage' : 'storage' } };
    case 'texture':
      return { ...base, texture: { sampleType: spec.sampleType, viewDimension: '2d' } };
    case 'sampler':
      return { ...base, sampler: { type: spec.comparison ? 'comparison' : 'filtering' } };
    case 'storageTexture':
      return { ...base, storageTexture: { access: 'write-only', format: spec.format, viewDimension: '2d' } };
  }
}

/** Binding names of one bind group of a set, in binding order. */
export function rasterGroupBindings(set: RasterBindingSet, group: number): string[] {
  return Object.entries(rasterBindings)
    .filter(([, s]) => s.set === set && s.group === group)
    .sort((a, b) => a[1].binding - b[1].binding)
    .map(([name]) => name);
}

/** Bind group layout of one group of a set: every binding the table lists for it. */
export function createRasterGroupLayout(device: GPUDevice, set: RasterBindingSet, group: number): GPUBindGroupLayout {
  const entries = rasterGroupBindings(set, group).map((name) => layoutEntry(rasterBindings[name]!));
  return device.createBindGroupLayout({ label: `raster ${set} group ${group}`, entries });
}
