import { GpuRendererError } from '../../errors/gpu-renderer-error.ts';
import { displayBindings } from '../../shaders/display-bindings.ts';
import { createProgramBindGroups, type PathTracerResourceMap } from '../../shaders/program-bind-groups.ts';
import { preferredCanvasFormat, type CanvasLike } from './canvas-target.ts';
import type { KernelPipeline } from '../../shaders/program-pipelines.ts';
import { createPresentPipeline } from './pipelines.ts';

const displayBindingOf = (name: string): number => displayBindings[name as keyof typeof displayBindings].binding;

/** Which image the display shows: the raw accumulation or the denoiser's output (a copy). */
export type DisplaySource = 'raw' | 'denoised';

/**
 * The display side of the film: the compute resolve into RGBA8 pixels (readPixels) and the canvas
 * presentation (a full-screen triangle), both tone mapping (or, for the linear presentation
 * output, only exposing) in the same WGSL. The source is the raw film or the denoised copy, which
 * the resolve reads the same way (the denoiser stores (rgb, 1)).
 */
export class FilmDisplay {
  private readonly device: GPUDevice;
  private readonly sources: Partial<Record<DisplaySource, PathTracerResourceMap>>;
  private readonly resolveGroups: Partial<Record<DisplaySource, GPUBindGroup[]>> = {};
  private readonly resolve: KernelPipeline;
  private canvas: { context: GPUCanvasContext; pipeline: GPURenderPipeline; groups: Partial<Record<DisplaySource, GPUBindGroup[]>> } | null = null;
  source: DisplaySource = 'raw';

  /** `resources` maps displayFilm to the raw film; `denoised`, when given, is the denoised buffer. */
  constructor(device: GPUDevice, resolve: KernelPipeline, resources: PathTracerResourceMap, denoised?: GPUBuffer) {
    this.device = device;
    this.resolve = resolve;
    this.sources = { raw: resources, ...(denoised ? { denoised: { ...resources, displayFilm: denoised } } : {}) };
    for (const [name, map] of Object.entries(this.sources) as [DisplaySource, PathTracerResourceMap][]) {
      this.resolveGroups[name] = createProgramBindGroups(device, resolve, map, displayBindingOf, `resolve.${name}`);
    }
  }

  get hasCanvas(): boolean {
    return this.canvas !== null;
  }

  async attachCanvas(canvas: CanvasLike, width: number, height: number): Promise<void> {
    const context = canvas.getContext('webgpu');
    if (!context) throw new GpuRendererError('INVALID_CANVAS', 'the canvas has no WebGPU context', { field: 'canvas' });
    canvas.width = width;
    canvas.height = height;
    const format = preferredCanvasFormat();
    context.configure({ device: this.device, format, alphaMode: 'opaque' });
    const { pipeline, layout } = await createPresentPipeline(this.device, format);
    const groups: Partial<Record<DisplaySource, GPUBindGroup[]>> = {};
    for (const [name, map] of Object.entries(this.sources) as [DisplaySource, PathTracerResourceMap][]) {
      groups[name] = createProgramBindGroups(this.device, layout, map, displayBindingOf, `present.${name}`);
    }
    this.canvas = { context, pipeline, groups };
  }

  /** Draws the current source into the canvas's current texture (nothing without a canvas). */
  encodePresent(encoder: GPUCommandEncoder): void {
    if (!this.canvas) return;
    const pass = encoder.beginRenderPass({
      colorAttachments: [{ view: this.canvas.context.getCurrentTexture().createView(), loadOp: 'clear', storeOp: 'store', clearValue: { r: 0, g: 0, b: 0, a: 1 } }],
    });
    pass.setPipeline(this.canvas.pipeline);
    this.canvas.groups[this.source]!.forEach((g, i) => pass.setBindGroup(i, g));
    pass.draw(3);
    pass.end();
  }

  /** Resolves the current source into the display pixel buffer. */
  encodeResolve(encoder: GPUCommandEncoder, width: number, height: number): void {
    const pass = encoder.beginComputePass();
    pass.setPipeline(this.resolve.pipeline);
    this.resolveGroups[this.source]!.forEach((g, i) => pass.setBindGroup(i, g));
    pass.dispatchWorkgroups(Math.ceil(width / 8), Math.ceil(height / 8));
    pass.end();
  }

  detach(): void {
    this.canvas?.context.unconfigure();
    this.canvas = null;
  }
}
