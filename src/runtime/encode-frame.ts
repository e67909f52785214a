import type { RendererRgba } from './clear-color.ts';
import type { GpuRendererFormat, GpuRendererOptions, GpuRendererSize, RendererFrameInfo } from './renderer-types.ts';
import type { RenderTarget } from './render-target.ts';

/**
 * The GPU half of one frame: acquire the target texture, open a render pass cleared to the clear
 * colour, let the host encode into it, close it and submit. With opaque presentation the alpha
 * channel is forced to 1 (it would be ignored by the compositor anyway, WebGPU spec
 * GPUCanvasAlphaMode "opaque"); with premultiplied presentation the colour is premultiplied.
 */
export function encodeAndSubmitFrame(args: {
  device: GPUDevice;
  target: RenderTarget;
  format: GpuRendererFormat;
  size: GpuRendererSize;
  clearColor: RendererRgba;
  alpha: boolean;
  info: RendererFrameInfo;
  onBeforeEncode: GpuRendererOptions['onBeforeEncode'];
}): void {
  const { device, target, format, size, clearColor, alpha, info, onBeforeEncode } = args;
  const [r, g, b, a] = clearColor;
  const clearValue = alpha ? { r: r * a, g: g * a, b: b * a, a } : { r, g, b, a: 1 };
  const texture = target.getCurrentTexture();
  const view = texture.createView();
  const encoder = device.createCommandEncoder({ label: info.frameId });
  const pass = encoder.beginRenderPass({
    label: `${info.frameId} main pass`,
    colorAttachments: [{ view, clearValue, loadOp: 'clear', storeOp: 'store' }],
  });
  try {
    onBeforeEncode?.({ ...info, device, encoder, pass, texture, view, format, size });
  } finally {
    pass.end();
  }
  device.queue.submit([encoder.finish()]);
}
