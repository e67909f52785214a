// The canvas present pass: the film (or its denoised copy) drawn by a fullscreen triangle.
import { ShaderStage } from '../../gpu/webgpu-constants.ts';
import { displayBindings } from '../../shaders/display-bindings.ts';
import { programLayout, programModule, type ProgramLayout } from '../../shaders/program-pipelines.ts';

/** Render pipeline drawing the display resolve into a canvas texture of `format`. */
export async function createPresentPipeline(device: GPUDevice, format: GPUTextureFormat): Promise<{ pipeline: GPURenderPipeline; layout: ProgramLayout }> {
  const layout = programLayout(device, displayBindings, 'present', ShaderStage.FRAGMENT);
  const module = await programModule(device, 'present');
  const pipeline = await device.createRenderPipelineAsync({
    label: 'present',
    layout: layout.layout,
    vertex: { module, entryPoint: 'present_vertex' },
    fragment: { module, entryPoint: 'present_fragment', targets: [{ format }] },
    primitive: { topology: 'triangle-list' },
  });
  return { pipeline, layout };
}
