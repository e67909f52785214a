export { supportsWebGpu, type SupportsWebGpuOptions } from './supports-webgpu.ts';
export { acquireGpuDevice, getGpu, type AcquireGpuDeviceOptions, type AcquiredGpuDevice } from './acquire-device.ts';
