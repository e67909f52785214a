/**
 * Raster pipelines, built from the generated programs and the binding table's group layouts:
 * forward shading (per blend mode, cull mode and winding), shadow depth, background, resolve, and
 * the compute programs (skinning, IBL precomputation).
 */
import { generatedRasterPrograms } from '../shaders/raster-programs.generated.ts';
import type { RasterProgramName } from '../shaders/raster-programs.ts';
import { createRasterGroupLayout } from './raster-bindings.ts';

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

const entryPoints = {
  skin: 'skin_vertices',
  iblDownsample: 'downsample',
  iblPrefilter: 'prefilter',
  iblIrradiance: 'project_irradiance',
  brdfLut: 'integrate_brdf',
} as const;

export function createRasterPipelines(device: GPUDevice, sampleCount: number): RasterPipelines {
  const modules = new Map<RasterProgramName, GPUShaderModule>();
  const module = (name: RasterProgramName): GPUShaderModule => {
    let m = modules.get(name);
    if (m === undefined) {
      m = device.createShaderModule({ label: `raster ${name}`, code: generatedRasterPrograms[name].wgsl });
      modules.set(name, m);
    }
    return m;
  };
  const drawLayouts = [0, 1, 2].map((g) => createRasterGroupLayout(device, 'draw', g));
  const drawPipelineLayout = device.createPipelineLayout({ label: 'raster draw', bindGroupLayouts: drawLayouts });
  const skinLayout = createRasterGroupLayout(device, 'skin', 0);
  const iblLayout = createRasterGroupLayout(device, 'ibl', 0);
  const resolveLayout = createRasterGroupLayout(device, 'resolve', 0);
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
          vertex: { module: module('forward'), entryPoint: 'vs_main', buffers: vertexBufferLayouts },
          fragment: {
            module: module('forward'),
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
          vertex: { module: module('shadow'), entryPoint: 'vs_shadow', buffers: [vertexBufferLayouts[0]!] },
          primitive: { topology: 'triangle-list', cullMode: 'none' },
          depthStencil: { format: SHADOW_FORMAT, depthWriteEnabled: true, depthCompare: 'less' },
        }),
      ),
    background: () =>
      cached('background', () =>
        device.createRenderPipeline({
          label: 'raster background',
          layout: drawPipelineLayout,
          vertex: { module: module('background'), entryPoint: 'vs_background' },
          fragment: { module: module('background'), entryPoint: 'fs_background', targets: [{ format: HDR_FORMAT }] },
          primitive: { topology: 'triangle-list' },
          depthStencil: { format: DEPTH_FORMAT, depthWriteEnabled: false, depthCompare: 'less-equal' },
          multisample,
        }),
      ),
    resolve: (format) =>
      cached(`resolve:${format}`, () =>
        device.createRenderPipeline({
          label: 'raster resolve',
          layout: device.createPipelineLayout({ bindGroupLayouts: [resolveLayout] }),
          vertex: { module: module('resolve'), entryPoint: 'vs_resolve' },
          fragment: { module: module('resolve'), entryPoint: 'fs_resolve', targets: [{ format }] },
          primitive: { topology: 'triangle-list' },
        }),
      ),
    compute: (name) =>
      cached(`compute:${name}`, () =>
        device.createComputePipeline({
          label: `raster ${name}`,
          layout: device.createPipelineLayout({ bindGroupLayouts: [name === 'skin' ? skinLayout : iblLayout] }),
          compute: { module: module(name), entryPoint: entryPoints[name] },
        }),
      ),
  };
}
