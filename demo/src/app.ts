// The demo application: the current scene, the orbit camera, the view that draws, and the
// features' panel sections, wired together. Everything renderer-specific lives in the view;
// everything optional lives in a feature (see extensions.ts).
import type { WavefrontPathTracingOptions } from '@plasius/gpu-renderer';
import type { CurrentImage, DemoContext, DemoFeature, DemoView, RadianceSource, RenderSettings, ViewHost } from './extensions.ts';
import type { DisplaySettings } from './film-view.ts';
import { OrbitCamera } from './orbit-camera.ts';
import { attachOrbitControls } from './orbit-controls.ts';
import { Readouts } from './readouts.ts';
import type { DemoScene } from './scenes/types.ts';

const rawRadiance: RadianceSource = (renderer) => renderer.readRadiance();

export interface DemoElements {
  viewport: HTMLElement;
  panel: HTMLElement;
  readouts: HTMLElement;
  notes: HTMLElement;
}

export class DemoApp {
  readonly display: DisplaySettings = { toneMapping: 'neutral', exposureEv: 0 };
  readonly settings: RenderSettings;
  readonly readouts: Readouts;
  private scene: DemoScene | null = null;
  private orbit: OrbitCamera | null = null;
  private view: DemoView;
  private readonly viewHost: ViewHost;
  private readonly features: readonly DemoFeature[];
  private readonly context: DemoContext;

  constructor(elements: DemoElements, options: { settings: RenderSettings; features: readonly DemoFeature[]; view: DemoView }) {
    this.settings = options.settings;
    this.features = options.features;
    this.view = options.view;
    this.readouts = new Readouts(elements.readouts, elements.notes);
    const currentScene = (): DemoScene | null => this.scene;
    this.context = {
      display: this.display,
      settings: this.settings,
      get scene() {
        return currentScene();
      },
      rebuild: () => this.view.rebuild(),
      redisplay: () => this.view.redisplay(),
      setExposure: (exposureEv) => {
        this.display.exposureEv = exposureEv;
        for (const feature of this.features) feature.displayChanged?.();
        this.view.redisplay();
      },
      resume: () => this.view.resume(),
      currentImage: (): CurrentImage | null => this.view.currentImage(),
    };
    this.viewHost = {
      element: elements.viewport,
      context: this.context,
      rendererOptions: () => this.rendererOptions(),
      radianceSource: () => this.features.reduce<RadianceSource | undefined>((source, f) => f.radianceSource?.() ?? source, undefined) ?? rawRadiance,
      onProgress: (p) => this.readouts.progress(p),
      onStatus: (text, kind) => this.readouts.status(text, kind),
      onNotes: (notes) => this.readouts.setNotes(notes),
    };
    this.view.start(this.viewHost);
    attachOrbitControls(
      elements.viewport,
      () => this.orbit ?? new OrbitCamera({ position: [0, 0, 1], target: [0, 0, 0] }),
      () => this.orbit && this.view.setCamera(this.orbit.camera()),
      () => this.resetCamera(),
    );
  }

  /** Adds every feature's controls to the panel. */
  mountFeatures(panel: HTMLElement): void {
    for (const feature of this.features) feature.mount(panel, this.context);
  }

  showScene(scene: DemoScene): void {
    this.scene = scene;
    this.orbit = new OrbitCamera(scene.description.camera);
    for (const feature of this.features) feature.sceneLoaded?.(scene);
    this.view.setScene(scene, this.orbit.camera());
  }

  /** Replaces the view (path traced, raster, ...), keeping the scene and the camera. */
  switchView(view: DemoView): void {
    this.view.stop();
    this.view = view;
    view.start(this.viewHost);
    if (this.scene && this.orbit) view.setScene(this.scene, this.orbit.camera());
  }

  /** Back to the scene's own camera. */
  resetCamera(): void {
    if (!this.scene) return;
    this.orbit = new OrbitCamera(this.scene.description.camera);
    this.view.setCamera(this.orbit.camera());
  }

  status(text: string, kind: 'busy' | 'ok' | 'error'): void {
    this.readouts.status(text, kind);
  }

  private async rendererOptions(): Promise<Partial<WavefrontPathTracingOptions>> {
    const parts = await Promise.all(this.features.map((f) => f.rendererOptions?.() ?? {}));
    return Object.assign({}, ...parts) as Partial<WavefrontPathTracingOptions>;
  }
}
