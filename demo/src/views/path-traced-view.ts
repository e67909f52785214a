// The progressive path-traced view: one renderer at a time, driven by a single loop so that
// scene rebuilds, camera moves and frames never overlap. Each frame adds `samplesPerFrame` samples
// per pixel, reads the linear estimate back and shows it; a camera move restarts accumulation.
import { type WavefrontCameraInput, type WavefrontPathTracingRenderer } from '@plasius/gpu-renderer';
import type { CurrentImage, DemoView, ViewHost } from '../extensions.ts';
import { FilmView } from '../film-view.ts';
import { createRendererLeavingOutUnsupported } from '../renderable-scene.ts';
import type { DemoScene } from '../scenes/types.ts';
import { nextFrame, ViewDevice, Wakeup } from './view-loop.ts';

export class PathTracedView implements DemoView {
  readonly id = 'path-traced';
  readonly label = 'Path traced';
  private host: ViewHost | null = null;
  private film: FilmView | null = null;
  private renderer: WavefrontPathTracingRenderer | null = null;
  private readonly device = new ViewDevice((error) => this.fail(error));
  private scene: DemoScene | null = null;
  private camera: WavefrontCameraInput | null = null;
  private pending: { rebuild: boolean; camera: boolean } = { rebuild: false, camera: false };
  private readonly wakeup = new Wakeup();
  private stopped = false;
  private failed = false;
  private progress = { samples: 0, frames: 0, startedAt: 0, lastFrameAt: 0, rays: 0, renderMs: 0 };
  private restarts = 0;
  /** Adaptive sampling's pixels still sampling after the last frame (null without it). */
  private activePixels: number | null = null;

  start(host: ViewHost): void {
    this.host = host;
    this.film = new FilmView(host.element);
    void this.loop();
  }

  setScene(scene: DemoScene, camera: WavefrontCameraInput): void {
    this.scene = scene;
    this.camera = camera;
    this.rebuild();
  }

  rebuild(): void {
    this.pending.rebuild = true;
    this.failed = false;
    this.wakeup.wake();
  }

  setCamera(camera: WavefrontCameraInput): void {
    this.camera = camera;
    this.pending.camera = true;
    this.wakeup.wake();
  }

  redisplay(): void {
    if (this.host) this.film?.present(this.host.context.display);
  }

  resume(): void {
    this.wakeup.wake();
  }

  currentImage(): CurrentImage | null {
    const radiance = this.film?.currentRadiance;
    const pixels = this.film?.currentPixels;
    if (!radiance || !pixels || !this.scene) return null;
    // With the denoiser on, this is the denoised estimate (what is shown).
    return { radiance, pixels, samples: this.progress.samples, sceneName: this.scene.name };
  }

  stop(): void {
    this.stopped = true;
    this.wakeup.wake();
    this.renderer?.destroy();
    this.renderer = null;
    this.film?.destroy();
    this.device.destroy();
  }

  private get wantsFrame(): boolean {
    const max = this.host?.context.settings.maxSamples ?? 0;
    return this.renderer !== null && !this.failed && (max === 0 || this.progress.samples < max) && this.activePixels !== 0;
  }

  private async loop(): Promise<void> {
    while (!this.stopped) {
      try {
        if (this.pending.rebuild) await this.createRenderer();
        if (this.pending.camera && this.renderer && this.camera) {
          this.pending.camera = false;
          this.renderer.updateCamera(this.camera);
          this.resetProgress();
        }
        if (this.wantsFrame) await this.renderFrame();
        else {
          this.report(true);
          await this.wakeup.sleep();
          continue;
        }
      } catch (error) {
        this.fail(error);
      }
      // Let the page handle input between frames.
      await nextFrame();
    }
  }

  private async createRenderer(): Promise<void> {
    const host = this.host!;
    this.pending.rebuild = false;
    this.pending.camera = false;
    this.renderer?.destroy();
    this.renderer = null;
    if (!this.scene || !this.camera) return;
    const { settings } = host.context;
    host.onStatus(`Preparing ${this.scene.name}…`, 'busy');
    this.resetProgress();
    // Options can wait for a download (an HDRI map); a newer rebuild supersedes this one.
    const options = await host.rendererOptions();
    if (this.pending.rebuild || this.stopped) return;
    const device = await this.device.acquire();
    const started = performance.now();
    const { renderer, omitted } = await createRendererLeavingOutUnsupported({
      ...this.scene.description,
      ...options,
      camera: this.camera,
      width: settings.width,
      height: settings.height,
      maxDepth: settings.maxDepth,
      samplesPerPixel: settings.samplesPerFrame,
      device,
    });
    if (this.pending.rebuild || this.stopped) {
      // Superseded while it was being built.
      renderer.destroy();
      return;
    }
    this.renderer = renderer;
    const snapshot = renderer.getSnapshot();
    host.onNotes([...this.scene.notes, ...omitted, ...snapshot.warnings]);
    host.onStatus(`${snapshot.triangleCount.toLocaleString('en')} triangles, ready in ${Math.round(performance.now() - started)} ms · ${snapshot.adapter}`, 'ok');
    this.film?.clear();
    this.resetProgress();
  }

  private async renderFrame(): Promise<void> {
    const host = this.host!;
    const renderer = this.renderer!;
    const stats = await renderer.renderFrame({ samplesPerPixel: host.context.settings.samplesPerFrame });
    // A rebuild or camera move that came in meanwhile makes this frame stale.
    if (renderer !== this.renderer || this.pending.camera) return;
    const radiance = await host.radianceSource()(renderer);
    if (renderer !== this.renderer || this.pending.camera) return;
    this.film!.show(radiance, host.context.display);
    this.progress.samples = stats.samplesAccumulated;
    this.activePixels = stats.adaptive ? stats.adaptive.activePixels : null;
    this.progress.frames += 1;
    this.progress.rays += stats.rays.total;
    this.progress.renderMs += stats.wallTimeMs;
    this.progress.lastFrameAt = performance.now();
    this.report(false);
  }

  private resetProgress(): void {
    const now = performance.now();
    this.progress = { samples: 0, frames: 0, startedAt: now, lastFrameAt: now, rays: 0, renderMs: 0 };
    this.restarts += 1;
    this.activePixels = null;
    this.report(false);
  }

  private report(idle: boolean): void {
    const p = this.progress;
    const seconds = p.renderMs / 1000;
    const pixels = this.host?.context.settings ? this.host.context.settings.width * this.host.context.settings.height : 0;
    this.host?.onProgress({
      restarts: this.restarts,
      ...(this.activePixels !== null ? { activePixels: { active: this.activePixels, total: pixels } } : {}),
      samples: p.samples,
      frames: p.frames,
      elapsedMs: (idle ? p.lastFrameAt : performance.now()) - p.startedAt,
      raysPerSecond: seconds > 0 ? p.rays / seconds : 0,
      samplesPerSecond: seconds > 0 ? (p.samples * pixels) / seconds : 0,
      idle,
    });
  }

  private fail(error: unknown): void {
    this.failed = true;
    const message = error instanceof Error ? error.message : String(error);
    console.error(error);
    this.host?.onStatus(message, 'error');
  }
}
