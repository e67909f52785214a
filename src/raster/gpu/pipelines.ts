/**
 * Raster pipelines, built on the shared GPU-program layer (src/shaders/program-pipelines.ts): the
 * programs' modules (compiled once per device, WGSL errors as typed errors) and each binding set's
 * layouts: forward shading (per blend mode, cull mode and winding), shadow depth, background,
 * resolve, and the compute programs (skinning, IBL precomputation).
 */
import { ShaderStage } from '../../gpu/webgpu-constants.ts';
import { programLayout, programModule } from '../../shaders/program-pipelines.ts';
import type { ProgramName } from '../../shaders/programs.ts';
import { rasterBindings, rasterSetBindings } from './raster-bindings.ts';

export const HDR_FORMAT: GPUTextureFormat = 'rgba16float';
export const DEPTH_FORMAT: GPUTextureFormat = 'depth24plus';
export const SHADOW_FORMAT: GPUTextureFormat = 'depth32float';

/** Vertex buffers of every drawn mesh: one float stream per attribute. */
export const vertexBufferLayouts: GPUVertexBufferLayout[] = [
  { arrayStride: 12, attributes: [{ shaderLocation: 0, offset: 0, format: 'float32x3' }] },
  { arrayStride: 12, attributes: [{ shaderLocation: 1, offset: 0, format: 'float32x3' }] },
  { arrayStride: 16, attributes: [{ shaderLocation: 2, offset: 0, format: 'float32x4' }] },
  { arrayStride: 8, attributes: [{ shaderLocation: 3, offset: 0, format: 'float32x2' }] },
  { arrayStride: 8, attributes: [{ shaderLocation: 4, offset: 0, format: 'float32x2' }] },
  { arrayStride: 16, attributes: [{ shaderLocation: 5, offset: 0, format: 'float32x4' }] },
];

export interface ForwardKey {
  blend: boolean;
  doubleSided: boolean;
  mirrored: boolean;
}

export interface RasterPipelines {
  readonly drawLayouts: GPUBindGroupLayout[];
  readonly skinLayout: GPUBindGroupLayout;
  readonly iblLayout: GPUBindGroupLayout;
  readonly resolveLayout: GPUBindGroupLayout;
  forward(key: ForwardKey): GPURenderPipeline;
  shadow(): GPURenderPipeline;
  background(): GPURenderPipeline;
  resolve(format: GPUTextureFormat): GPURenderPipeline;
  compute(name: 'skin' | 'iblDownsample' | 'iblPrefilter' | 'iblIrradiance' | 'brdfLut'): GPUComputePipeline;
}

const computePrograms = {
  skin: { program: 'rasterSkin', entryPoint: 'skin_vertices' },
  iblDownsample: { program: 'rasterIblDownsample', entryPoint: 'downsample' },
  iblPrefilter: { program: 'rasterIblPrefilter', entryPoint: 'prefilter' },
  iblIrradiance: { program: 'rasterIblIrradiance', entryPoint: 'project_irradiance' },
  brdfLut: { program: 'rasterBrdfLut', entryPoint: 'integrate_brdf' },
} as const satisfies Record<string, { program: ProgramName; entryPoint: string }>;

const rasterPrograms = ['rasterForward', 'rasterShadow', 'rasterBackground', 'rasterResolve', ...Object.values(computePrograms).map((c) => c.program)] as const;
type RasterProgram = (typeof rasterPrograms)[number];

/** Compiles every raster program (their WGSL loads with the first renderer) and builds the layouts. */
export async function createRasterPipelines(device: GPUDevice, sampleCount: number): Promise<RasterPipelines> {
  const compiled = await Promise.all(rasterPrograms.map(async (name) => [name, await programModule(device, name)] as const));
  const modules = new Map<RasterProgram, GPUShaderModule>(compiled);
  const module = (name: RasterProgram): GPUShaderModule => modules.get(name)!;
  // Each binding set's layouts hold the whole set, so one bind group serves every program of it.
  const draw = programLayout(device, rasterBindings, 'rasterForward', ShaderStage.VERTEX | ShaderStage.FRAGMENT, rasterSetBindings('draw'));
  const drawLayouts = draw.groups;
  const drawPipelineLayout = draw.layout;
  const skin = programLayout(device, rasterBindings, 'rasterSkin', ShaderStage.COMPUTE, rasterSetBindings('skin'));
  const ibl = programLayout(device, rasterBindings, 'rasterIblPrefilter', ShaderStage.COMPUTE, rasterSetBindings('ibl'));
  const resolve = programLayout(device, rasterBindings, 'rasterResolve', ShaderStage.FRAGMENT, rasterSetBindings('resolve'));
  const [skinLayout, iblLayout, resolveLayout] = [skin.groups[0]!, ibl.groups[0]!, resolve.groups[0]!];
  const cache = new Map<string, GPURenderPipeline | GPUComputePipeline>();
  const cached = <T extends GPURenderPipeline | GPUComputePipeline>(key: string, make: () => T): T => {
    let p = cache.get(key) as T | undefined;
    if (p === undefined) {
      p = make();
      cache.set(key, p);
    }
    return p;
  };
  const multisample = { count: sampleCount };
  return {
    drawLayouts,
    skinLayout,
    iblLayout,
    resolveLayout,
    forward: (key) =>
      cached(`forward:${key.blend}:${key.doubleSided}:${key.mirrored}`, () =>
        device.createRenderPipeline({
          label: 'raster forward',
          layout: drawPipelineLayout,
          vertex: { module: module('rasterForward'), entryPoint: 'vs_main', buffers: vertexBufferLayouts },
          fragment: {
            module: module('rasterForward'),
            entryPoint: 'fs_main',
            targets: [
              key.blend
                ? { format: HDR_FORMAT, blend: { color: { srcFactor: 'one', dstFactor: 'one-minus-src-alpha' }, alpha: { srcFactor: 'one', dstFactor: 'one-minus-src-alpha' } } }
                : { format: HDR_FORMAT },
            ],
          },
          primitive: { topology: 'triangle-list', cullMode: key.doubleSided ? 'none' : 'back', frontFace: key.mirrored ? 'cw' : 'ccw' },
          depthStencil: { format: DEPTH_FORMAT, depthWriteEnabled: !key.blend, depthCompare: 'less' },
          multisample,
        }),
      ),
    shadow: () =>
      cached('shadow', () =>
        device.createRenderPipeline({
          label: 'raster shadow',
          layout: drawPipelineLayout,
          vertex: { module: module('rasterShadow'), entryPoint: 'vs_shadow', buffers: [vertexBufferLayouts[0]!] },
          primitive: { topology: 'triangle-list', cullMode: 'none' },
          depthStencil: { format: SHADOW_FORMAT, depthWriteEnabled: true, depthCompare: 'less' },
        }),
      ),
    background: () =>
      cached('background', () =>
        device.createRenderPipeline({
          label: 'raster background',
          layout: drawPipelineLayout,
          vertex: { module: module('rasterBackground'), entryPoint: 'vs_background' },
          fragment: { module: module('rasterBackground'), entryPoint: 'fs_background', targets: [{ format: HDR_FORMAT }] },
          primitive: { topology: 'triangle-list' },
          depthStencil: { format: DEPTH_FORMAT, depthWriteEnabled: false, depthCompare: 'less-equal' },
          multisample,
        }),
      ),
    resolve: (format) =>
      cached(`resolve:${format}`, () =>
        device.createRenderPipeline({
          label: 'raster resolve',
          layout: resolve.layout,
          vertex: { module: module('rasterResolve'), entryPoint: 'vs_resolve' },
          fragment: { module: module('rasterResolve'), entryPoint: 'fs_resolve', targets: [{ format }] },
          primitive: { topology: 'triangle-list' },
        }),
      ),
    compute: (name) =>
      cached(`compute:${name}`, () =>
        device.createComputePipeline({
          label: `raster ${name}`,
          layout: name === 'skin' ? skin.layout : ibl.layout,
          compute: { module: module(computePrograms[name].program), entryPoint: computePrograms[name].entryPoint },
        }),
      ),
  };
}
