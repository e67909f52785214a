/**
 * Duck-typed contract of an XR manager (as @plasius/gpu-xr's `createXrManager` provides): a store
 * whose state names the active WebXR session (an `XRSession`, or null/undefined when none).
 */
export interface XrManagerState {
  readonly activeSession?: unknown;
}

export interface XrManagerLike {
  /** Registers a listener called on every state change; returns the unsubscribe function. */
  subscribe(listener: (state?: XrManagerState) => void): () => void;
  getState(): XrManagerState;
}

export interface XrSessionEvent {
  /** The manager's `activeSession` at the transition (the session that started or ended). */
  readonly session: unknown;
}

export interface XrBindingOptions {
  onSessionStart?: (event: XrSessionEvent) => void;
  onSessionEnd?: (event: XrSessionEvent) => void;
}

/** What the binding needs from a renderer. */
export interface XrBindableRenderer {
  setXrActive(active: boolean): void;
}
