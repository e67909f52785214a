import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { TextureUsage } from '../gpu/webgpu-constants.ts';
import type { GpuRendererCanvas, GpuRendererFormat } from './renderer-types.ts';

/**
 * Where frames go: a configured WebGPU canvas context, or an offscreen texture (Node.js, workers
 * without a canvas, tests). `release` gives the target back: the canvas context is unconfigured so
 * a renderer created later on the same canvas starts from a clean configuration (WebGPU spec,
 * GPUCanvasContext.unconfigure), the offscreen texture is destroyed.
 */
export interface RenderTarget {
  readonly kind: 'canvas' | 'offscreen';
  readonly width: number;
  readonly height: number;
  getCurrentTexture(): GPUTexture;
  setSize(width: number, height: number): void;
  release(): void;
}

interface CanvasLike {
  width: number;
  height: number;
  getContext(kind: 'webgpu'): GPUCanvasContext | null;
}

export function resolveCanvas(canvas: GpuRendererCanvas): CanvasLike {
  let element: unknown = canvas;
  if (typeof canvas === 'string') {
    const doc = (globalThis as { document?: { querySelector(selector: string): unknown } }).document;
    if (!doc) throw new GpuRendererError('INVALID_CANVAS', `cannot resolve selector ${JSON.stringify(canvas)} without a document`, { field: 'canvas' });
    try {
      element = doc.querySelector(canvas);
    } catch (cause) {
      throw new GpuRendererError('INVALID_CANVAS', `invalid selector ${JSON.stringify(canvas)}`, { field: 'canvas', cause });
    }
    if (!element) throw new GpuRendererError('INVALID_CANVAS', `no element matches ${JSON.stringify(canvas)}`, { field: 'canvas' });
  }
  if (typeof element !== 'object' || element === null || typeof (element as CanvasLike).getContext !== 'function') {
    throw new GpuRendererError('INVALID_CANVAS', 'expected a canvas element, an OffscreenCanvas or a selector of one', { field: 'canvas' });
  }
  return element as CanvasLike;
}

export function createCanvasTarget(canvas: CanvasLike, device: GPUDevice, format: GpuRendererFormat, alpha: boolean): RenderTarget {
  const context = canvas.getContext('webgpu');
  if (!context) throw new GpuRendererError('INVALID_CANVAS', 'the canvas has no WebGPU context (is another context already in use?)', { field: 'canvas' });
  context.configure({
    device,
    format,
    alphaMode: alpha ? 'premultiplied' : 'opaque',
    usage: TextureUsage.RENDER_ATTACHMENT | TextureUsage.COPY_SRC,
  });
  let configured = true;
  return {
    kind: 'canvas',
    get width() {
      return canvas.width;
    },
    get height() {
      return canvas.height;
    },
    getCurrentTexture: () => context.getCurrentTexture(),
    setSize(width, height) {
      // The context picks up the new drawing-buffer size at the next getCurrentTexture().
      canvas.width = width;
      canvas.height = height;
    },
    release() {
      if (!configured) return;
      configured = false;
      context.unconfigure();
    },
  };
}

export function createOffscreenTarget(device: GPUDevice, format: GpuRendererFormat, width: number, height: number): RenderTarget {
  const make = (w: number, h: number): GPUTexture =>
    device.createTexture({
      label: 'gpu-renderer offscreen target',
      size: { width: w, height: h },
      format,
      usage: TextureUsage.RENDER_ATTACHMENT | TextureUsage.COPY_SRC | TextureUsage.TEXTURE_BINDING,
    });
  let texture: GPUTexture | undefined = make(width, height);
  let size = { width, height };
  return {
    kind: 'offscreen',
    get width() {
      return size.width;
    },
    get height() {
      return size.height;
    },
    getCurrentTexture() {
      if (!texture) throw new GpuRendererError('INVALID_STATE', 'the offscreen target was released');
      return texture;
    },
    setSize(w, h) {
      if (!texture || (w === size.width && h === size.height)) return;
      texture.destroy();
      texture = make(w, h);
      size = { width: w, height: h };
    },
    release() {
      texture?.destroy();
      texture = undefined;
    },
  };
}
