// What one choice of the environment feature's "Light" picker is (environment.ts lists them; the
// HDRI maps and the sky presets are sources of their own files).
import type { WavefrontPathTracingOptions } from '@plasius/gpu-renderer';
import type { DemoContext } from '../extensions.ts';
import type { DemoScene } from '../scenes/types.ts';

export interface EnvironmentSource {
  id: string;
  label: string;
  /** Adds the source's controls to `parent` (shown only while the source is selected). */
  mount(parent: HTMLElement, context: DemoContext, params: URLSearchParams): void;
  /** May wait for a download or a decode (the renderer is built once it resolves). */
  rendererOptions(): Partial<WavefrontPathTracingOptions> | Promise<Partial<WavefrontPathTracingOptions>>;
  sceneLoaded?(scene: DemoScene): void;
  /** Exposure in stops the source looks right at; undefined: the scene's suggestion. */
  exposureEv?(): number | undefined;
}
