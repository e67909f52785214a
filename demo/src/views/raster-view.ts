// The raster view: the same scene, camera, environment, tone mapping and exposure drawn by the
// package's forward WebGPU rasteriser (createRasterRenderer, README "Raster renderer and animated
// scenes") for an interactive preview. It renders offscreen and shows the pixels on a 2D canvas
// (the PNG export saves them). The rasteriser has no global illumination: emissive surfaces glow
// but light nothing, so a scene lit only by emitters (the Cornell box) needs a sky or HDRI here.
// Tone mapping and exposure are fixed when it is created, so display changes rebuild it (cheap).
// A scene it cannot take (analytic scene objects, a material extension it refuses) gets a status
// line naming why, never a blank picture.
import {
  createRasterRenderer,
  GpuRendererError,
  type RasterRenderer,
  type RasterRendererOptions,
  type WavefrontCameraInput,
  type WavefrontPathTracingOptions,
} from '@plasius/gpu-renderer';
import type { CurrentImage, DemoView, ViewHost } from '../extensions.ts';
import type { DemoScene } from '../scenes/types.ts';
import { nextFrame, ViewDevice, Wakeup } from './view-loop.ts';

/** The scene keys the rasteriser draws; anything else in a scene it cannot show. */
const sceneKeys = ['meshes', 'instances', 'materials', 'textures', 'images', 'lights'] as const;
const environmentKeys = ['environment', 'environmentMap', 'environmentLighting'] as const;

/** Why the rasteriser cannot draw this scene, or null. */
export function rasterUnsupported(scene: DemoScene): string | null {
  const description = scene.description as unknown as Record<string, unknown>;
  const objects = description.sceneObjects;
  if (Array.isArray(objects) && objects.length > 0) return `it has ${objects.length} analytic scene object(s) (sceneObjects), which the rasteriser does not draw; it draws meshes`;
  if (!Array.isArray(description.meshes) || description.meshes.length === 0) return 'it has no meshes';
  return null;
}

/** Raster options for a scene, the path tracer's environment options and the display settings. */
export function rasterOptions(scene: DemoScene, camera: WavefrontCameraInput, options: Partial<WavefrontPathTracingOptions>, display: { toneMapping: RasterRendererOptions['toneMapping']; exposureEv: number }, size: { width: number; height: number }): RasterRendererOptions {
  const result: Record<string, unknown> = { camera, width: size.width, height: size.height, toneMapping: display.toneMapping, exposure: 2 ** display.exposureEv };
  const description = scene.description as unknown as Record<string, unknown>;
  for (const key of sceneKeys) if (description[key] !== undefined) result[key] = description[key];
  for (const key of environmentKeys) if (options[key] !== undefined) result[key] = options[key];
  return result as unknown as RasterRendererOptions;
}

export class RasterView implements DemoView {
  readonly id = 'raster';
  readonly label = 'Raster preview';
  private host: ViewHost | null = null;
  private canvas: HTMLCanvasElement | null = null;
  private pixels: ImageData | null = null;
  private renderer: RasterRenderer | null = null;
  private readonly device = new ViewDevice((error) => this.fail(error));
  private scene: DemoScene | null = null;
  private camera: WavefrontCameraInput | null = null;
  private pending = { rebuild: false, draw: false };
  private readonly wakeup = new Wakeup();
  private stopped = false;
  private frames = 0;
  private restarts = 0;
  private startedAt = 0;

  start(host: ViewHost): void {
    this.host = host;
    this.canvas = document.createElement('canvas');
    this.canvas.className = 'film';
    this.canvas.dataset.view = 'raster';
    host.element.append(this.canvas);
    void this.loop();
  }

  setScene(scene: DemoScene, camera: WavefrontCameraInput): void {
    this.scene = scene;
    this.camera = camera;
    this.rebuild();
  }

  rebuild(): void {
    this.pending.rebuild = true;
    this.wakeup.wake();
  }

  setCamera(camera: WavefrontCameraInput): void {
    this.camera = camera;
    this.pending.draw = true;
    this.wakeup.wake();
  }

  // Tone mapping and exposure are creation options of the rasteriser.
  redisplay(): void {
    this.rebuild();
  }

  resume(): void {}

  currentImage(): CurrentImage | null {
    if (!this.pixels || !this.scene) return null;
    return { radiance: null, pixels: this.pixels, samples: 0, sceneName: `${this.scene.name}-raster` };
  }

  stop(): void {
    this.stopped = true;
    this.wakeup.wake();
    this.renderer?.destroy();
    this.renderer = null;
    this.canvas?.remove();
    this.device.destroy();
  }

  private async loop(): Promise<void> {
    while (!this.stopped) {
      try {
        if (this.pending.rebuild) await this.createRenderer();
        if (this.pending.draw && this.renderer) await this.draw();
        else if (!this.pending.rebuild) {
          await this.wakeup.sleep();
          continue;
        }
      } catch (error) {
        this.fail(error);
      }
      await nextFrame();
    }
  }

  private async createRenderer(): Promise<void> {
    const host = this.host!;
    this.pending.rebuild = false;
    this.renderer?.destroy();
    this.renderer = null;
    if (!this.scene || !this.camera) return;
    const unsupported = rasterUnsupported(this.scene);
    if (unsupported) {
      this.clear();
      host.onStatus(`The raster view cannot draw ${this.scene.name}: ${unsupported}. Switch to the path-traced view.`, 'error');
      return;
    }
    host.onStatus(`Preparing the raster view of ${this.scene.name}…`, 'busy');
    const options = await host.rendererOptions();
    if (this.pending.rebuild || this.stopped) return;
    const device = await this.device.acquire();
    const { settings, display } = host.context;
    const started = performance.now();
    let renderer: RasterRenderer;
    try {
      renderer = await createRasterRenderer({ ...rasterOptions(this.scene, this.camera, options, display, settings), device });
    } catch (error) {
      if (!(error instanceof GpuRendererError)) throw error;
      // The scene is valid for the path tracer but not for the rasteriser: say which part.
      this.clear();
      host.onStatus(`The raster view cannot draw ${this.scene.name}: ${error.message}${error.field ? ` (${error.field})` : ''}. Switch to the path-traced view.`, 'error');
      return;
    }
    if (this.pending.rebuild || this.stopped) {
      renderer.destroy();
      return;
    }
    this.renderer = renderer;
    const lit = options.environmentMap !== undefined || options.environmentLighting !== undefined || (options.environment?.color ?? []).some((c) => c > 0) || (this.scene.description.lights?.length ?? 0) > 0;
    host.onNotes([
      ...this.scene.notes,
      ...(lit ? [] : ['Raster view: emissive surfaces glow but light nothing (no global illumination). Choose a sky or an HDRI map to light the scene.']),
    ]);
    host.onStatus(`Raster view ready in ${Math.round(performance.now() - started)} ms`, 'ok');
    this.restarts += 1;
    this.frames = 0;
    this.startedAt = performance.now();
    this.pending.draw = true;
  }

  private async draw(): Promise<void> {
    const renderer = this.renderer!;
    this.pending.draw = false;
    if (this.camera) renderer.setCamera(this.camera);
    const stats = await renderer.render();
    const read = await renderer.readPixels();
    if (renderer !== this.renderer) return;
    const data = read.data instanceof Uint8Array ? new Uint8ClampedArray(read.data.buffer, read.data.byteOffset, read.data.byteLength) : Uint8ClampedArray.from(read.data, (v) => v * 255);
    this.pixels = new ImageData(data.slice() as Uint8ClampedArray<ArrayBuffer>, read.width, read.height);
    const canvas = this.canvas!;
    if (canvas.width !== read.width || canvas.height !== read.height) {
      canvas.width = read.width;
      canvas.height = read.height;
    }
    canvas.getContext('2d')!.putImageData(this.pixels, 0, 0);
    this.frames += 1;
    this.host?.onProgress({
      samples: this.frames,
      frames: this.frames,
      elapsedMs: performance.now() - this.startedAt,
      raysPerSecond: 0,
      samplesPerSecond: 0,
      idle: true,
      restarts: this.restarts,
      frameTimeMs: stats.frameTimeMs,
      detail: `${stats.drawCalls} draw calls · ${stats.triangles.toLocaleString('en')} triangles`,
    });
  }

  private clear(): void {
    this.pixels = null;
    this.canvas?.getContext('2d')?.clearRect(0, 0, this.canvas.width, this.canvas.height);
  }

  private fail(error: unknown): void {
    const message = error instanceof Error ? error.message : String(error);
    console.error(error);
    this.host?.onStatus(message, 'error');
  }
}
