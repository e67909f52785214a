export { bindRendererToXrManager } from './bind-xr-manager.ts';
export type { XrManagerLike, XrManagerState, XrBindingOptions, XrSessionEvent, XrBindableRenderer } from './xr-types.ts';
