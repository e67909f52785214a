import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { displayBindings } from '../shaders/display-bindings.ts';
import { createProgramBindGroups, type PathTracerResourceMap } from './bind-groups.ts';
import { preferredCanvasFormat, type CanvasLike } from './canvas-target.ts';
import { createPresentPipeline, type KernelPipeline } from './pipelines.ts';

const displayBindingOf = (name: string): number => displayBindings[name as keyof typeof displayBindings].binding;

/**
 * The display side of the film: the compute resolve into RGBA8 pixels (readPixels) and the canvas
 * presentation (a full-screen triangle), both tone mapping in the same WGSL.
 */
export class FilmDisplay {
  private readonly device: GPUDevice;
  private readonly resources: PathTracerResourceMap;
  private readonly resolveGroups: GPUBindGroup[];
  private readonly resolve: KernelPipeline;
  private canvas: { context: GPUCanvasContext; pipeline: GPURenderPipeline; groups: GPUBindGroup[] } | null = null;

  constructor(device: GPUDevice, resolve: KernelPipeline, resources: PathTracerResourceMap) {
    this.device = device;
    this.resolve = resolve;
    this.resources = resources;
    this.resolveGroups = createProgramBindGroups(device, resolve, resources, displayBindingOf, 'resolve');
  }

  async attachCanvas(canvas: CanvasLike, width: number, height: number): Promise<void> {
    const context = canvas.getContext('webgpu');
    if (!context) throw new GpuRendererError('INVALID_CANVAS', 'the canvas has no WebGPU context', { field: 'canvas' });
    canvas.width = width;
    canvas.height = height;
    const format = preferredCanvasFormat();
    context.configure({ device: this.device, format, alphaMode: 'opaque' });
    const { pipeline, layout } = await createPresentPipeline(this.device, format);
    this.canvas = { context, pipeline, groups: createProgramBindGroups(this.device, layout, this.resources, displayBindingOf, 'present') };
  }

  /** Draws the film into the canvas's current texture (nothing without a canvas). */
  encodePresent(encoder: GPUCommandEncoder): void {
    if (!this.canvas) return;
    const pass = encoder.beginRenderPass({
      colorAttachments: [{ view: this.canvas.context.getCurrentTexture().createView(), loadOp: 'clear', storeOp: 'store', clearValue: { r: 0, g: 0, b: 0, a: 1 } }],
    });
    pass.setPipeline(this.canvas.pipeline);
    this.canvas.groups.forEach((g, i) => pass.setBindGroup(i, g));
    pass.draw(3);
    pass.end();
  }

  /** Resolves the film into the display pixel buffer. */
  encodeResolve(encoder: GPUCommandEncoder, width: number, height: number): void {
    const pass = encoder.beginComputePass();
    pass.setPipeline(this.resolve.pipeline);
    this.resolveGroups.forEach((g, i) => pass.setBindGroup(i, g));
    pass.dispatchWorkgroups(Math.ceil(width / 8), Math.ceil(height / 8));
    pass.end();
  }

  detach(): void {
    this.canvas?.context.unconfigure();
    this.canvas = null;
  }
}
