export { createGpuRenderer } from './create-gpu-renderer.ts';
export { createRendererDebugHooks, type RendererDebugHooks, type RendererDebugHookOptions, type RendererDebugSession, type RendererDebugFrameSample, type RendererFrameTimeGovernor } from './debug-hooks.ts';
export { parseClearColor, type RendererClearColorInput, type RendererRgba } from './clear-color.ts';
export { gpuRendererFormats } from './validate-options.ts';
export type {
  GpuRenderer,
  GpuRendererOptions,
  GpuRendererSnapshot,
  GpuRendererSize,
  GpuRendererFormat,
  GpuRendererCanvas,
  GpuRendererDeviceState,
  RendererFrameIdInput,
  RendererFrameInfo,
  RendererEncodeContext,
  RendererFrameResult,
  RendererDeviceLostInfo,
  RendererPixels,
} from './renderer-types.ts';
