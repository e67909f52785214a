export { GpuRendererError, isGpuRendererError, type GpuRendererErrorCode } from './gpu-renderer-error.ts';
