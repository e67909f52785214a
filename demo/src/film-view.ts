// Shows the renderer's linear radiance on a 2D canvas, tone mapped on the CPU with the package's
// own mirror of its display shader (encodeRadianceToRgba8). Keeping the linear image on the page
// makes display changes (tone mapping, exposure) instant, without losing a sample, and gives the
// exporters the exact radiance (EXR) and the exact displayed pixels (PNG).
import { encodeRadianceToRgba8, type LinearRgbaImage, type WavefrontToneMapping } from '@plasius/gpu-renderer';

export interface DisplaySettings {
  toneMapping: WavefrontToneMapping;
  /** Stops: radiance is multiplied by 2^exposureEv before tone mapping. */
  exposureEv: number;
}

export class FilmView {
  readonly canvas: HTMLCanvasElement;
  private readonly context: CanvasRenderingContext2D;
  private radiance: LinearRgbaImage | null = null;
  private pixels: ImageData | null = null;

  constructor(host: HTMLElement) {
    this.canvas = document.createElement('canvas');
    this.canvas.className = 'film';
    this.canvas.dataset.view = 'film';
    host.append(this.canvas);
    const context = this.canvas.getContext('2d');
    if (!context) throw new Error('no 2D canvas context');
    this.context = context;
  }

  /** Shows a new estimate. */
  show(radiance: LinearRgbaImage, settings: DisplaySettings): void {
    this.radiance = radiance;
    this.present(settings);
  }

  /** Shows the current estimate again with other display settings. */
  present(settings: DisplaySettings): void {
    const radiance = this.radiance;
    if (!radiance) return;
    const rgba = encodeRadianceToRgba8(radiance.data, { toneMapping: settings.toneMapping, exposureEv: settings.exposureEv });
    this.pixels = new ImageData(rgba as Uint8ClampedArray<ArrayBuffer>, radiance.width, radiance.height);
    if (this.canvas.width !== radiance.width || this.canvas.height !== radiance.height) {
      this.canvas.width = radiance.width;
      this.canvas.height = radiance.height;
    }
    this.context.putImageData(this.pixels, 0, 0);
  }

  clear(): void {
    this.radiance = null;
    this.pixels = null;
    this.context.clearRect(0, 0, this.canvas.width, this.canvas.height);
  }

  /** The linear estimate on screen (RGBA float32, top row first). */
  get currentRadiance(): LinearRgbaImage | null {
    return this.radiance;
  }

  /** The displayed sRGB pixels. */
  get currentPixels(): ImageData | null {
    return this.pixels;
  }

  destroy(): void {
    this.canvas.remove();
  }
}
