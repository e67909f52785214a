// The demo's extension points. A feature of the renderer reaches the page through one of these,
// each a few lines in its own module:
//
// - DemoFeature (features/index.ts): a control panel section that contributes renderer options
//   and/or display behaviour: environment (EnvironmentSources in features/environment.ts: uniform
//   colour, HDRI maps, sun and sky presets), tone mapping and exposure, denoise, render settings
//   (with adaptive sampling), export.
// - Exporter (features/export.ts, `exporters`): a save button (PNG and EXR).
// - DemoView (views/index.ts, `demoViews`): what draws the scene: the progressive path tracer and
//   the raster preview; the view picker appears once there are two.
import type { LinearRgbaImage, WavefrontCameraInput, WavefrontPathTracingOptions, WavefrontPathTracingRenderer } from '@plasius/gpu-renderer';
import type { DisplaySettings } from './film-view.ts';
import type { DemoScene } from './scenes/types.ts';

export interface RenderSettings {
  width: number;
  height: number;
  /** Scattering events per path. */
  maxDepth: number;
  /** Samples per pixel each frame adds. */
  samplesPerFrame: number;
  /** Stop accumulating at this many samples per pixel (0: never). */
  maxSamples: number;
}

/** The image on screen, for exporters. */
export interface CurrentImage {
  /** Linear radiance; null for views that only have display pixels (the raster view). */
  radiance: LinearRgbaImage | null;
  pixels: ImageData;
  samples: number;
  sceneName: string;
}

/** Where the displayed radiance comes from (the raw estimate by default). */
export type RadianceSource = (renderer: WavefrontPathTracingRenderer) => Promise<LinearRgbaImage>;

/** What the app offers features. */
export interface DemoContext {
  readonly display: DisplaySettings;
  readonly settings: RenderSettings;
  readonly scene: DemoScene | null;
  /** A scene-level option changed: the renderer is created again and accumulation restarts. */
  rebuild(): void;
  /** A display setting changed: the current image is shown again (no new samples needed). */
  redisplay(): void;
  /** Sets the exposure (stops), updating the exposure control, and shows the image again. */
  setExposure(exposureEv: number): void;
  /** A loop setting changed (samples per frame, stop point): rendering resumes if it had stopped. */
  resume(): void;
  currentImage(): CurrentImage | null;
}

export interface DemoFeature {
  id: string;
  /** Adds the feature's controls to the panel (once, at start). */
  mount(panel: HTMLElement, context: DemoContext): void;
  /** Renderer options merged in whenever the renderer is created (may wait for a download). */
  rendererOptions?(): Partial<WavefrontPathTracingOptions> | Promise<Partial<WavefrontPathTracingOptions>>;
  /** The display settings were changed from outside the feature's controls (setExposure). */
  displayChanged?(): void;
  /** A new scene was loaded; adopt its suggestions. */
  sceneLoaded?(scene: DemoScene): void;
  /** Replaces the displayed radiance (the last feature that returns one wins). */
  radianceSource?(): RadianceSource | undefined;
}

/** Progress of the view, for the readouts. */
export interface ViewProgress {
  samples: number;
  frames: number;
  /** Wall-clock time since accumulation restarted. */
  elapsedMs: number;
  /** Rays traced per second of rendering (camera, extension and shadow rays). */
  raysPerSecond: number;
  samplesPerSecond: number;
  /** Converged to the stop point, or paused. */
  idle: boolean;
  /** Counts restarts of accumulation (rebuilds, camera moves): a new value means a new image. */
  restarts: number;
  /** Adaptive sampling: pixels still sampling, of all pixels (absent without it). */
  activePixels?: { active: number; total: number };
  /** Views that draw whole frames (raster): the frame time, shown instead of samples. */
  frameTimeMs?: number;
  /** Replaces the rays/s readout (raster: draw calls and triangles). */
  detail?: string;
}

/** What a view needs from the app. */
export interface ViewHost {
  element: HTMLElement;
  context: DemoContext;
  rendererOptions(): Promise<Partial<WavefrontPathTracingOptions>>;
  radianceSource(): RadianceSource;
  onProgress(progress: ViewProgress): void;
  onStatus(text: string, kind: 'busy' | 'ok' | 'error'): void;
  onNotes(notes: string[]): void;
}

export interface DemoView {
  id: string;
  label: string;
  start(host: ViewHost): void;
  /** Shows a scene from a camera (the renderer or raster pipeline is rebuilt). */
  setScene(scene: DemoScene, camera: WavefrontCameraInput): void;
  /** Renderer options changed: rebuild with the same scene and camera. */
  rebuild(): void;
  setCamera(camera: WavefrontCameraInput): void;
  redisplay(): void;
  resume(): void;
  currentImage(): CurrentImage | null;
  stop(): void;
}
