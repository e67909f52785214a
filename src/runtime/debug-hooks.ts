import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import type { GpuRendererOptions, RendererFrameResult } from './renderer-types.ts';

/** One frame sample as the debug session (@plasius/gpu-debug) records it. */
export interface RendererDebugFrameSample {
  readonly frameId: string;
  readonly frameTimeMs: number;
  readonly targetFrameTimeMs: number | undefined;
}

/** Duck-typed contract of a @plasius/gpu-debug session: only `recordFrame` is used. */
export interface RendererDebugSession {
  recordFrame(sample: RendererDebugFrameSample): void;
}

/** Duck-typed contract of a @plasius/gpu-performance frame-time governor. */
export interface RendererFrameTimeGovernor {
  getSnapshot(): { readonly targetFrameTimeMs: number };
}

export interface RendererDebugHookOptions {
  debugSession: RendererDebugSession;
  /** Negotiated frame-time target; takes precedence over `governor`. */
  getTargetFrameTimeMs?: () => number | undefined;
  governor?: RendererFrameTimeGovernor;
}

export type RendererDebugHooks = Required<Pick<GpuRendererOptions, 'onFrameComplete' | 'getTargetFrameTimeMs'>>;

/**
 * Hooks to spread into `createGpuRenderer` options: each completed frame is recorded into the debug
 * session with its id, its measured frame time and the target in force when the frame started.
 * Spreading replaces the host's own `onFrameComplete`/`getTargetFrameTimeMs`; compose by calling
 * the returned hooks from your own when you need both.
 */
export function createRendererDebugHooks(options: RendererDebugHookOptions): RendererDebugHooks {
  if (typeof options !== 'object' || options === null) throw new GpuRendererError('INVALID_OPTION', 'expected an options object', { field: 'options' });
  const { debugSession, getTargetFrameTimeMs, governor } = options;
  if (typeof debugSession !== 'object' || debugSession === null || typeof debugSession.recordFrame !== 'function') {
    throw new GpuRendererError('INVALID_OPTION', 'expected a debug session with recordFrame(sample)', { field: 'debugSession' });
  }
  if (getTargetFrameTimeMs !== undefined && typeof getTargetFrameTimeMs !== 'function') {
    throw new GpuRendererError('INVALID_OPTION', 'expected a function', { field: 'getTargetFrameTimeMs' });
  }
  if (governor !== undefined && (typeof governor !== 'object' || governor === null || typeof governor.getSnapshot !== 'function')) {
    throw new GpuRendererError('INVALID_OPTION', 'expected a governor with getSnapshot()', { field: 'governor' });
  }
  const target = (): number | undefined => (getTargetFrameTimeMs ? getTargetFrameTimeMs() : governor?.getSnapshot().targetFrameTimeMs);
  return {
    getTargetFrameTimeMs: target,
    onFrameComplete: (result: RendererFrameResult) => {
      debugSession.recordFrame({ frameId: result.frameId, frameTimeMs: result.frameTimeMs, targetFrameTimeMs: result.targetFrameTimeMs });
    },
  };
}
