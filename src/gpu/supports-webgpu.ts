import { getGpu } from './acquire-device.ts';

export interface SupportsWebGpuOptions {
  /** Also require that an adapter can be obtained (default true). */
  requireAdapter?: boolean;
  powerPreference?: GPUPowerPreference;
}

/** Whether WebGPU, and by default an adapter, is available here (browser, worker or Node.js + Dawn). */
export async function supportsWebGpu(options: SupportsWebGpuOptions = {}): Promise<boolean> {
  const gpu = await getGpu();
  if (!gpu) return false;
  if (options.requireAdapter === false) return true;
  try {
    const adapter = await gpu.requestAdapter(options.powerPreference ? { powerPreference: options.powerPreference } : undefined);
    return adapter !== null;
  } catch {
    return false;
  }
}
