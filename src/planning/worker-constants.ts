/**
 * Identity of the renderer inside the sibling scheduling/debug packages (@plasius/gpu-worker,
 * @plasius/gpu-performance, @plasius/gpu-debug): its queue class, its debug owner tag and defaults.
 */
export const rendererWorkerQueueClass = 'render';
export const rendererDebugOwner = 'renderer';

export type RendererWorkerProfileName = 'realtime' | 'xr';
export const defaultRendererWorkerProfile: RendererWorkerProfileName = 'realtime';

/** Linear RGBA clear colour used when `createGpuRenderer` gets none: opaque black. */
export const defaultRendererClearColor: readonly [number, number, number, number] = Object.freeze([0, 0, 0, 1] as [number, number, number, number]);
