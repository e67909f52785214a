/**
 * Every resource binding of the path tracer, in bind groups ordered by update frequency (static
 * geometry; materials and textures; per-frame camera, lights and environment; per-dispatch
 * transport state). The WGSL declarations (`package::layout::bindings`) are generated from this
 * table; a kernel imports the bindings it uses, and the build reflects which ones survived linking,
 * so pipeline layouts are derived, never listed by hand.
 */

export const bindGroupIndices = {
  geometry: 0,
  materials: 1,
  frame: 2,
  transport: 3,
} as const;

export type BindGroupName = keyof typeof bindGroupIndices;

export type BindingKind =
  | { kind: 'uniform'; type: string; dynamic?: boolean }
  | { kind: 'storage'; type: string; access: 'read' | 'read_write' }
  | { kind: 'texture'; type: string; sampleType: GPUTextureSampleType; viewDimension?: GPUTextureViewDimension }
  | { kind: 'sampler'; comparison?: boolean }
  | { kind: 'storageTexture'; format: GPUTextureFormat };

/**
 * One binding of a binding table (every GPU program's tables use this shape). `group` is a bind
 * group index (the path tracer uses bindGroupIndices); `visibility` (ShaderStage bits) is set where
 * a table's bind group layouts are shared by programs of several stages, and otherwise the stage of
 * the program the layout is built for.
 */
export type BindingSpec = { group: number; binding: number; doc: string; visibility?: number } & BindingKind;

const G = bindGroupIndices;

export const pathTracerBindings = {
  // Group 0: geometry, uploaded once per scene.
  primitives: { group: G.geometry, binding: 0, kind: 'storage', access: 'read', type: 'array<Primitive>', doc: 'traceable primitives in BVH order' },
  bvhNodes: { group: G.geometry, binding: 1, kind: 'storage', access: 'read', type: 'array<BvhNode>', doc: 'flattened binary BVH' },
  bvhParents: { group: G.geometry, binding: 2, kind: 'storage', access: 'read', type: 'array<u32>', doc: 'parent of every BVH node (root: INDEX_NONE), for stackless traversal' },
  alphaPrimitives: { group: G.geometry, binding: 3, kind: 'storage', access: 'read', type: 'array<AlphaPrimitive>', doc: 'alpha-test data of MASK and BLEND primitives' },
  instances: { group: G.geometry, binding: 4, kind: 'storage', access: 'read', type: 'array<Instance>', doc: 'mesh placements' },
  indices: { group: G.geometry, binding: 5, kind: 'storage', access: 'read', type: 'array<u32>', doc: 'triangle lists of every mesh' },
  vertexStreams: { group: G.geometry, binding: 6, kind: 'storage', access: 'read', type: 'array<u32>', doc: 'vertex attribute streams of every mesh (instances hold the stream offsets)' },
  // Group 1: materials and textures.
  materials: { group: G.materials, binding: 0, kind: 'storage', access: 'read', type: 'array<vec4f>', doc: 'material heap: cores, extension blocks, texture bindings, texture infos' },
  textureAtlas: { group: G.materials, binding: 1, kind: 'texture', type: 'texture_2d_array<f32>', sampleType: 'unfilterable-float', viewDimension: '2d-array', doc: 'every material texture with its mip chain (rgba8unorm)' },
  // Group 2: per frame.
  frame: { group: G.frame, binding: 0, kind: 'uniform', type: 'FrameUniforms', doc: 'camera, environment, lights, scene extents' },
  lights: { group: G.frame, binding: 1, kind: 'storage', access: 'read', type: 'array<vec4f>', doc: 'lights heap: emitters, selection tables, light tree, environment tables, portals' },
  lighting: { group: G.frame, binding: 2, kind: 'uniform', type: 'LightingUniforms', doc: 'where the lights heap keeps each kind of emitter, the sun, selection probabilities' },
  environmentTexture: { group: G.frame, binding: 3, kind: 'texture', type: 'texture_2d<f32>', sampleType: 'unfilterable-float', viewDimension: '2d', doc: 'environment map radiance (rgba32float, equirectangular, row 0 = +Y)' },
  // Group 3: transport state, per dispatch.
  paths: { group: G.transport, binding: 0, kind: 'storage', access: 'read_write', type: 'array<PathRecord>', doc: 'every path of the wave: state, next ray and its hit, pending shadow ray, sample' },
  queues: { group: G.transport, binding: 1, kind: 'storage', access: 'read_write', type: 'array<atomic<u32>>', doc: 'statistics, per-bounce queue lengths, then the ray and shadow queues (path slots)' },
  shadingDispatch: { group: G.transport, binding: 2, kind: 'storage', access: 'read_write', type: 'array<u32>', doc: 'per bounce, the workgroup counts of its shading dispatch (indirect arguments: x, y, z), sized from its queue lengths' },
  film: { group: G.transport, binding: 7, kind: 'storage', access: 'read_write', type: 'array<FilmPixel>', doc: 'full-frame accumulation: radiance sum, sample count' },
  filmAovs: { group: G.transport, binding: 11, kind: 'storage', access: 'read_write', type: 'array<FilmAovPixel>', doc: 'AOV sums per pixel' },
  wave: { group: G.transport, binding: 9, kind: 'uniform', dynamic: true, type: 'WaveUniforms', doc: 'per-wave constants' },
  bounce: { group: G.transport, binding: 10, kind: 'uniform', dynamic: true, type: 'BounceUniforms', doc: 'per-bounce constants' },
  // Output: film moments and ids, adaptive sampling, denoising. A buffer of one record stands in
  // where a feature is off.
  filmMoments: { group: G.transport, binding: 16, kind: 'storage', access: 'read_write', type: 'array<FilmMoments>', doc: 'moment sums per pixel' },
  filmIds: { group: G.transport, binding: 17, kind: 'storage', access: 'read_write', type: 'array<u32>', doc: 'per pixel: 1 + instance index of the first sample that reached a non-specular hit (0: none)' },
  adaptive: { group: G.transport, binding: 18, kind: 'uniform', type: 'AdaptiveUniforms', doc: 'adaptive-sampling convergence constants' },
  adaptiveError: { group: G.transport, binding: 19, kind: 'storage', access: 'read_write', type: 'array<f32>', doc: 'per-pixel error estimate of the last convergence test' },
  adaptivePixels: { group: G.transport, binding: 20, kind: 'storage', access: 'read_write', type: 'array<atomic<u32>>', doc: 'counts (ADAPTIVE_* slots), then the indices of the pixels still sampling' },
  denoise: { group: G.transport, binding: 21, kind: 'uniform', type: 'DenoiseUniforms', doc: 'constants of one denoiser pass' },
  denoiseColor: { group: G.transport, binding: 22, kind: 'storage', access: 'read_write', type: 'array<vec4f>', doc: 'two halves: demodulated radiance and its luminance variance' },
  denoiseGuide: { group: G.transport, binding: 23, kind: 'storage', access: 'read_write', type: 'array<DenoiseGuide>', doc: 'a-trous guides per pixel' },
  denoised: { group: G.transport, binding: 24, kind: 'storage', access: 'read_write', type: 'array<vec4f>', doc: 'denoised radiance (rgb, 1)' },
  denoiseEnergy: { group: G.transport, binding: 25, kind: 'storage', access: 'read_write', type: 'array<vec4f>', doc: 'a-trous energy: [0] the per-channel scale, then per 8x8 workgroup the raw and the filtered reflected radiance sums' },
} as const satisfies Record<string, BindingSpec>;

export type PathTracerBindingName = keyof typeof pathTracerBindings;

/** The generated WGSL declaration of one binding. */
export function bindingDeclaration(name: string, spec: BindingSpec): string {
  const at = `@group(${spec.group}) @binding(${spec.binding})`;
  const comment = `// ${spec.doc}`;
  if (spec.kind === 'uniform') return `${comment}\n${at} var<uniform> ${name}: ${spec.type};`;
  if (spec.kind === 'storage') return `${comment}\n${at} var<storage, ${spec.access}> ${name}: ${spec.type};`;
  if (spec.kind === 'sampler') return `${comment}\n${at} var ${name}: ${spec.comparison ? 'sampler_comparison' : 'sampler'};`;
  if (spec.kind === 'storageTexture') return `${comment}\n${at} var ${name}: texture_storage_2d<${spec.format}, write>;`;
  return `${comment}\n${at} var ${name}: ${spec.type};`;
}

/** The WebGPU layout entry of one binding (the spec's visibility, else `visibility`). */
export function bindingLayoutEntry(spec: BindingSpec, visibility: number): GPUBindGroupLayoutEntry {
  const base = { binding: spec.binding, visibility: spec.visibility ?? visibility };
  switch (spec.kind) {
    case 'uniform':
      return { ...base, buffer: { type: 'uniform', hasDynamicOffset: spec.dynamic === true } };
    case 'storage':
      return { ...base, buffer: { type: spec.access === 'read' ? 'read-only-storage' : 'storage' } };
    case 'texture':
      return { ...base, texture: { sampleType: spec.sampleType, viewDimension: spec.viewDimension ?? '2d' } };
    case 'sampler':
      return { ...base, sampler: { type: spec.comparison ? 'comparison' : 'filtering' } };
    case 'storageTexture':
      return { ...base, storageTexture: { access: 'write-only', format: spec.format, viewDimension: '2d' } };
  }
}
