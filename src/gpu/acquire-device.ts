import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { describe } from '../errors/validate.ts';
import { isNodeRuntime, nodeModule } from '../io/platform.ts';

export interface AcquireGpuDeviceOptions {
  /** Share an existing device instead of creating one. */
  device?: GPUDevice;
  powerPreference?: GPUPowerPreference;
  /** Features to enable when present on the adapter (missing ones are skipped, not errors); default timestamp-query and shader-f16. */
  optionalFeatures?: readonly GPUFeatureName[];
}

export interface AcquiredGpuDevice {
  device: GPUDevice;
  /** True when this library created the device and must destroy it. */
  ownsDevice: boolean;
  adapterDescription: string;
  timestampQueries: boolean;
  /** A CPU implementation (lavapipe, SwiftShader, WARP): the adapter says it is a fallback or software one. */
  softwareAdapter: boolean;
}

let nodeGpu: Promise<GPU | undefined> | undefined;

/**
 * The platform's `GPU` object: `navigator.gpu` in browsers and workers; in Node.js, Dawn through
 * the `webgpu` package (imported lazily so browser bundles never touch it).
 */
export function getGpu(): Promise<GPU | undefined> {
  const nav = (globalThis as { navigator?: { gpu?: GPU } }).navigator;
  if (nav?.gpu) return Promise.resolve(nav.gpu);
  if (!isNodeRuntime()) return Promise.resolve(undefined);
  nodeGpu ??= loadDawn();
  return nodeGpu;
}

async function loadDawn(): Promise<GPU | undefined> {
  try {
    const dawn = await nodeModule<{ create: (flags: string[]) => GPU; globals: Record<string, unknown> }>('webgpu');
    for (const [key, value] of Object.entries(dawn.globals)) {
      if (!(key in globalThis)) (globalThis as Record<string, unknown>)[key] = value;
    }
    return dawn.create([]);
  } catch {
    return undefined;
  }
}

export function describeAdapter(adapter: GPUAdapter): string {
  return describeAdapterInfo(adapter.info as Partial<GPUAdapterInfo> | undefined, 'unknown adapter');
}

/**
 * A shared `device` must be a GPUDevice (by shape: `features`, `limits`, `queue`, the create
 * methods; browsers and Dawn have their own classes) and `powerPreference` one of WebGPU's two.
 */
function validateDeviceOptions(options: AcquireGpuDeviceOptions): void {
  const d = options.device as unknown;
  if (d !== undefined) {
    const device = d as Partial<GPUDevice> | null;
    const ok = typeof device === 'object' && device !== null && typeof device.createCommandEncoder === 'function' && typeof device.createBuffer === 'function' &&
      typeof device.features?.has === 'function' && typeof device.limits === 'object' && device.limits !== null && typeof device.queue?.submit === 'function';
    if (!ok) throw new GpuRendererError('INVALID_OPTION', `expected a GPUDevice, got ${describe(d)}`, { field: 'device' });
  }
  const p = options.powerPreference as unknown;
  if (p !== undefined && p !== 'low-power' && p !== 'high-performance') {
    throw new GpuRendererError('INVALID_OPTION', `expected "low-power" or "high-performance", got ${describe(p)}`, { field: 'powerPreference' });
  }
}

export async function acquireGpuDevice(options: AcquireGpuDeviceOptions = {}): Promise<AcquiredGpuDevice> {
  validateDeviceOptions(options);
  if (options.device) {
    const device = options.device;
    return {
      device,
      ownsDevice: false,
      adapterDescription: describeAdapterInfo(device.adapterInfo, 'shared device'),
      timestampQueries: device.features.has('timestamp-query'),
      softwareAdapter: isSoftwareAdapter(device.adapterInfo),
    };
  }
  const gpu = await getGpu();
  if (!gpu) throw new GpuRendererError('WEBGPU_UNAVAILABLE', 'WebGPU is not available in this environment (no navigator.gpu and no Dawn).');
  const adapter = await gpu.requestAdapter(options.powerPreference ? { powerPreference: options.powerPreference } : undefined);
  if (!adapter) throw new GpuRendererError('WEBGPU_UNAVAILABLE', 'No WebGPU adapter is available.');
  // shader-f16: the OIDN denoiser's half-precision network (src/film/denoise/oidn).
  const wanted = options.optionalFeatures ?? ['timestamp-query', 'shader-f16'];
  const requiredFeatures = wanted.filter((f) => adapter.features.has(f));
  // Ask for the adapter's own storage limits: scenes are bounded by what the device really offers.
  const requiredLimits: Record<string, number> = {
    maxStorageBufferBindingSize: adapter.limits.maxStorageBufferBindingSize,
    maxBufferSize: adapter.limits.maxBufferSize,
    // 13 for the megakernel integrator (src/pathtracer/kernels/megakernel.wesl); 10 for the rest.
    maxStorageBuffersPerShaderStage: Math.min(adapter.limits.maxStorageBuffersPerShaderStage, 16),
  };
  const device = await adapter.requestDevice({ requiredFeatures, requiredLimits });
  return {
    device,
    ownsDevice: true,
    adapterDescription: describeAdapter(adapter),
    timestampQueries: device.features.has('timestamp-query'),
    softwareAdapter: isSoftwareAdapter(adapter.info),
  };
}

/** Whether the adapter runs on the CPU (GPUAdapterInfo.isFallbackAdapter, or a software architecture or driver name). */
export function isSoftwareAdapter(info: Partial<GPUAdapterInfo> | undefined): boolean {
  if (!info) return false;
  if ((info as { isFallbackAdapter?: boolean }).isFallbackAdapter === true) return true;
  const text = [info.architecture, info.device, info.description].filter((p) => typeof p === 'string').join(' ');
  return /software|llvmpipe|lavapipe|swiftshader|warp/i.test(text);
}

function describeAdapterInfo(info: Partial<GPUAdapterInfo> | undefined, fallback: string): string {
  const parts = [info?.vendor, info?.architecture, info?.device, info?.description].filter(
    (p): p is string => typeof p === 'string' && p.length > 0,
  );
  return parts.length > 0 ? [...new Set(parts)].join(' / ') : fallback;
}
