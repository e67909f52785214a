// Real WebGPU for tests: Dawn through the `webgpu` package (lavapipe where there is no GPU).
import { acquireGpuDevice } from '../../src/gpu/acquire-device.ts';
import { BufferUsage, MapMode } from '../../src/gpu/webgpu-constants.ts';

let shared: Promise<GPUDevice> | undefined;

/** One device shared by a test file; Dawn releases it when the process exits. */
export function testDevice(): Promise<GPUDevice> {
  shared ??= acquireGpuDevice().then((a) => a.device);
  return shared;
}

export async function createShaderChecked(device: GPUDevice, code: string): Promise<GPUShaderModule> {
  const module = device.createShaderModule({ code });
  const info = await module.getCompilationInfo();
  const errors = info.messages.filter((m) => m.type === 'error');
  if (errors.length > 0) {
    const lines = code.split('\n');
    throw new Error(errors.map((e) => `${e.lineNum}:${e.linePos} ${e.message}\n  ${lines[e.lineNum - 1] ?? ''}`).join('\n'));
  }
  return module;
}

export function uploadBuffer(device: GPUDevice, data: ArrayBuffer | ArrayBufferView, usage: number = BufferUsage.STORAGE): GPUBuffer {
  const bytes = data instanceof ArrayBuffer ? new Uint8Array(data) : new Uint8Array(data.buffer, data.byteOffset, data.byteLength);
  const size = Math.max(16, Math.ceil(bytes.byteLength / 4) * 4);
  const buffer = device.createBuffer({ size, usage: usage | BufferUsage.COPY_DST | BufferUsage.COPY_SRC, mappedAtCreation: true });
  new Uint8Array(buffer.getMappedRange()).set(bytes);
  buffer.unmap();
  return buffer;
}

export async function readBuffer(device: GPUDevice, buffer: GPUBuffer, size = buffer.size): Promise<ArrayBuffer> {
  const staging = device.createBuffer({ size, usage: BufferUsage.MAP_READ | BufferUsage.COPY_DST });
  const encoder = device.createCommandEncoder();
  encoder.copyBufferToBuffer(buffer, 0, staging, 0, size);
  device.queue.submit([encoder.finish()]);
  await staging.mapAsync(MapMode.READ);
  const copy = staging.getMappedRange().slice(0);
  staging.unmap();
  staging.destroy();
  return copy;
}

/** Runs a one-entry-point compute shader whose bindings all live in group 0, in binding order. */
export async function runCompute(
  device: GPUDevice,
  code: string,
  entryPoint: string,
  buffers: GPUBuffer[],
  workgroups: number,
  constants?: Record<string, number>,
): Promise<void> {
  const module = await createShaderChecked(device, code);
  device.pushErrorScope('validation');
  const pipeline = device.createComputePipeline({ layout: 'auto', compute: { module, entryPoint, ...(constants ? { constants } : {}) } });
  const bindGroup = device.createBindGroup({
    layout: pipeline.getBindGroupLayout(0),
    entries: buffers.map((buffer, binding) => ({ binding, resource: { buffer } })),
  });
  const encoder = device.createCommandEncoder();
  const pass = encoder.beginComputePass();
  pass.setPipeline(pipeline);
  pass.setBindGroup(0, bindGroup);
  pass.dispatchWorkgroups(workgroups);
  pass.end();
  device.queue.submit([encoder.finish()]);
  const error = await device.popErrorScope();
  if (error) throw new Error(error.message);
  await device.queue.onSubmittedWorkDone();
}
