import { GpuRendererError } from '../../errors/gpu-renderer-error.ts';

/** A canvas element, an OffscreenCanvas or a CSS selector of a canvas. */
export type CanvasTarget = HTMLCanvasElement | OffscreenCanvas | string;

export interface CanvasLike {
  width: number;
  height: number;
  getContext(kind: 'webgpu'): GPUCanvasContext | null;
}

/** Resolves a canvas element, OffscreenCanvas or CSS selector; typed error when it is none of them. */
export function resolveCanvasTarget(target: CanvasTarget, field = 'canvas'): CanvasLike {
  let canvas: unknown = target;
  if (typeof target === 'string') {
    const doc = (globalThis as { document?: { querySelector(s: string): unknown } }).document;
    if (!doc) throw new GpuRendererError('INVALID_CANVAS', `cannot resolve selector ${JSON.stringify(target)} without a document`, { field });
    canvas = doc.querySelector(target);
    if (!canvas) throw new GpuRendererError('INVALID_CANVAS', `no element matches ${JSON.stringify(target)}`, { field });
  }
  if (typeof canvas !== 'object' || canvas === null || typeof (canvas as CanvasLike).getContext !== 'function') {
    throw new GpuRendererError('INVALID_CANVAS', 'expected a canvas element, an OffscreenCanvas or a CSS selector', { field });
  }
  return canvas as CanvasLike;
}

export function preferredCanvasFormat(): GPUTextureFormat {
  const gpu = (globalThis as { navigator?: { gpu?: GPU } }).navigator?.gpu;
  return gpu?.getPreferredCanvasFormat ? gpu.getPreferredCanvasFormat() : 'bgra8unorm';
}
