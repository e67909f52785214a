import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { describe, requireInteger } from '../errors/validate.ts';
import type { GpuRendererFormat, GpuRendererOptions } from './renderer-types.ts';

export const gpuRendererFormats: readonly GpuRendererFormat[] = Object.freeze(['bgra8unorm', 'rgba8unorm', 'rgba16float'] as GpuRendererFormat[]);

const callbackFields = [
  'frameIdFactory',
  'onFrameStart',
  'onBeforeEncode',
  'onAfterSubmit',
  'onFrameComplete',
  'onDeviceLost',
  'onError',
  'getTargetFrameTimeMs',
  'requestAnimationFrame',
  'cancelAnimationFrame',
] as const;

const invalid = (field: string, message: string): never => {
  throw new GpuRendererError('INVALID_OPTION', message, { field });
};

/** Checks every option before any GPU work, so a bad option never leaves a half-built renderer. */
export function validateRendererOptions(options: unknown): GpuRendererOptions {
  if (options === undefined) return {};
  if (typeof options !== 'object' || options === null) return invalid('options', `expected an options object, got ${describe(options)}`);
  const o = options as GpuRendererOptions;
  for (const field of callbackFields) {
    if (o[field] !== undefined && typeof o[field] !== 'function') invalid(field, `expected a function, got ${describe(o[field])}`);
  }
  if (o.cancelAnimationFrame && !o.requestAnimationFrame) invalid('requestAnimationFrame', 'cancelAnimationFrame was given without requestAnimationFrame');
  if (o.format !== undefined && !gpuRendererFormats.includes(o.format)) {
    invalid('format', `expected one of ${gpuRendererFormats.join(', ')}, got ${describe(o.format)}`);
  }
  if (o.powerPreference !== undefined && o.powerPreference !== 'low-power' && o.powerPreference !== 'high-performance') {
    invalid('powerPreference', `expected "low-power" or "high-performance", got ${describe(o.powerPreference)}`);
  }
  if (o.alpha !== undefined && typeof o.alpha !== 'boolean') invalid('alpha', `expected a boolean, got ${describe(o.alpha)}`);
  if (o.device !== undefined && (typeof o.device !== 'object' || o.device === null || typeof (o.device as GPUDevice).createCommandEncoder !== 'function')) {
    invalid('device', `expected a GPUDevice, got ${describe(o.device)}`);
  }
  if (o.canvas !== undefined && typeof o.canvas !== 'string' && (typeof o.canvas !== 'object' || o.canvas === null)) {
    throw new GpuRendererError('INVALID_CANVAS', `expected a canvas, an OffscreenCanvas or a selector, got ${describe(o.canvas)}`, { field: 'canvas' });
  }
  if (o.target !== undefined) {
    if (o.canvas !== undefined) invalid('target', 'give either canvas or target, not both');
    if (typeof o.target !== 'object' || o.target === null) invalid('target', `expected { width, height }, got ${describe(o.target)}`);
    requireInteger(o.target.width, 'target.width', { min: 1 });
    requireInteger(o.target.height, 'target.height', { min: 1 });
  }
  return o;
}
