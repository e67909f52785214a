import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import type { XrBindableRenderer, XrBindingOptions, XrManagerLike } from './xr-types.ts';

/**
 * Follows an XR manager: while its state has an `activeSession` the renderer runs the `xr` frame
 * profile (frame ids and worker manifest follow), otherwise `realtime`. `onSessionStart` and
 * `onSessionEnd` fire once per transition, however many notifications the manager sends. The
 * returned function unbinds: it unsubscribes, returns the renderer to `realtime` and silences every
 * callback, including ones from a manager that keeps notifying stale listeners.
 */
export function bindRendererToXrManager(renderer: XrBindableRenderer, xrManager: XrManagerLike, options: XrBindingOptions = {}): () => void {
  if (typeof renderer !== 'object' || renderer === null || typeof renderer.setXrActive !== 'function') {
    throw new GpuRendererError('INVALID_OPTION', 'expected a renderer with setXrActive(active)', { field: 'renderer' });
  }
  if (typeof xrManager !== 'object' || xrManager === null || typeof xrManager.subscribe !== 'function' || typeof xrManager.getState !== 'function') {
    throw new GpuRendererError('INVALID_OPTION', 'expected an XR manager with subscribe(listener) and getState()', { field: 'xrManager' });
  }
  for (const key of ['onSessionStart', 'onSessionEnd'] as const) {
    if (options[key] !== undefined && typeof options[key] !== 'function') {
      throw new GpuRendererError('INVALID_OPTION', 'expected a function', { field: key });
    }
  }

  let bound = true;
  let active = false;
  let session: unknown = null;

  const sync = (): void => {
    if (!bound) return;
    // Read the state from the manager rather than trusting the listener argument: managers differ in
    // what they pass, but getState() is the contract.
    const next = xrManager.getState()?.activeSession ?? null;
    const nextActive = next !== null && next !== undefined;
    if (nextActive === active) return;
    active = nextActive;
    if (active) session = next;
    const event = { session: active ? next : session };
    renderer.setXrActive(active);
    if (active) options.onSessionStart?.(event);
    else options.onSessionEnd?.(event);
  };

  const unsubscribe = xrManager.subscribe(() => sync());
  if (typeof unsubscribe !== 'function') {
    throw new GpuRendererError('INVALID_OPTION', 'subscribe(listener) must return an unsubscribe function', { field: 'xrManager' });
  }
  sync();

  return () => {
    if (!bound) return;
    bound = false;
    unsubscribe();
    if (active) {
      active = false;
      renderer.setXrActive(false);
    }
  };
}
