import type { GpuRendererOptions } from './renderer-types.ts';

export interface AnimationFrameScheduler {
  request(callback: (timestamp: number) => void): unknown;
  cancel(handle: unknown): void;
}

const now = (): number => (typeof performance !== 'undefined' ? performance.now() : Date.now());

/**
 * Injected functions first (tests, XR sessions, custom loops), then the platform's
 * requestAnimationFrame, then a ~60 Hz timer where none exists (Node.js, some workers).
 */
export function resolveAnimationFrame(options: Pick<GpuRendererOptions, 'requestAnimationFrame' | 'cancelAnimationFrame'>): AnimationFrameScheduler {
  const g = globalThis as {
    requestAnimationFrame?: (cb: (t: number) => void) => number;
    cancelAnimationFrame?: (handle: number) => void;
  };
  if (options.requestAnimationFrame) {
    const request = options.requestAnimationFrame;
    const cancel = options.cancelAnimationFrame;
    return { request: (cb) => request(cb), cancel: (handle) => cancel?.(handle) };
  }
  if (typeof g.requestAnimationFrame === 'function') {
    return {
      request: (cb) => g.requestAnimationFrame!(cb),
      cancel: (handle) => g.cancelAnimationFrame?.(handle as number),
    };
  }
  return {
    request: (cb) => setTimeout(() => cb(now()), 1000 / 60),
    cancel: (handle) => clearTimeout(handle as ReturnType<typeof setTimeout>),
  };
}

export { now as rendererNow };
