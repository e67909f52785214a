import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { requireFiniteNumber } from '../errors/validate.ts';
import { acquireGpuDevice, getGpu } from '../gpu/acquire-device.ts';
import { defaultRendererClearColor, type RendererWorkerProfileName } from '../planning/worker-constants.ts';
import { getRendererWorkerManifest } from '../planning/worker-manifests.ts';
import { bindRendererToXrManager } from '../xr/bind-xr-manager.ts';
import { resolveAnimationFrame, rendererNow } from './animation-frame.ts';
import { parseClearColor, type RendererRgba } from './clear-color.ts';
import { encodeAndSubmitFrame } from './encode-frame.ts';
import { readTexturePixels } from './read-pixels.ts';
import { createCanvasTarget, createOffscreenTarget, resolveCanvas, type RenderTarget } from './render-target.ts';
import type {
  GpuRenderer,
  GpuRendererDeviceState,
  GpuRendererFormat,
  GpuRendererOptions,
  GpuRendererSize,
  RendererDeviceLostInfo,
  RendererFrameInfo,
  RendererFrameResult,
} from './renderer-types.ts';
import { validateRendererOptions } from './validate-options.ts';

const defaultOffscreenSize = { width: 300, height: 150 };

const defaultFrameId = ({ frame, profile }: { frame: number; profile: RendererWorkerProfileName }): string => `renderer.${profile}.${frame}`;

/**
 * Creates the realtime renderer: a device (shared or acquired), a target (canvas context or
 * offscreen texture) and a frame loop. Each frame runs onFrameStart -> (acquire, clear pass)
 * onBeforeEncode -> submit -> onAfterSubmit -> (queue done) onFrameComplete.
 */
export async function createGpuRenderer(rawOptions?: GpuRendererOptions): Promise<GpuRenderer> {
  const options = validateRendererOptions(rawOptions);
  let clearColor: RendererRgba = options.clearColor === undefined ? defaultRendererClearColor : parseClearColor(options.clearColor);
  const alpha = options.alpha ?? false;
  const canvas = options.canvas === undefined ? undefined : resolveCanvas(options.canvas);

  const acquired = await acquireGpuDevice({ device: options.device, powerPreference: options.powerPreference });
  const { device, ownsDevice } = acquired;
  let format: GpuRendererFormat;
  if (options.format) format = options.format;
  else if (canvas) format = ((await getGpu())?.getPreferredCanvasFormat() as GpuRendererFormat | undefined) ?? 'bgra8unorm';
  else format = 'rgba8unorm';

  let target: RenderTarget;
  try {
    target = canvas
      ? createCanvasTarget(canvas, device, format, alpha)
      : createOffscreenTarget(device, format, options.target?.width ?? defaultOffscreenSize.width, options.target?.height ?? defaultOffscreenSize.height);
  } catch (error) {
    if (ownsDevice) device.destroy();
    throw error;
  }

  const scheduler = resolveAnimationFrame(options);
  let size: GpuRendererSize = Object.freeze({ width: target.width, height: target.height, cssWidth: target.width, cssHeight: target.height, devicePixelRatio: 1 });
  let running = false;
  let frameHandle: unknown;
  let frame = 0;
  let lastFrameId: string | undefined;
  let lastTimestamp: number | undefined;
  let xrActive = false;
  let deviceState: GpuRendererDeviceState = 'ready';
  let deviceLost: RendererDeviceLostInfo | undefined;
  let destroyed = false;
  let unbindXr: (() => void) | undefined;

  const profile = (): RendererWorkerProfileName => (xrActive ? 'xr' : 'realtime');

  const stopLoop = (): void => {
    running = false;
    if (frameHandle !== undefined) scheduler.cancel(frameHandle);
    frameHandle = undefined;
  };

  const assertUsable = (): void => {
    if (destroyed) throw new GpuRendererError('RENDERER_DESTROYED', 'the renderer was destroyed');
    if (deviceState === 'lost') throw new GpuRendererError('DEVICE_LOST', `the GPU device was lost (${deviceLost?.reason ?? 'unknown'}): create a new renderer`);
  };

  // WebGPU spec, GPUDevice.lost: resolves once, with reason "destroyed" after device.destroy().
  void device.lost.then((info) => {
    if (destroyed) return;
    deviceState = 'lost';
    deviceLost = Object.freeze({ reason: info?.reason ?? 'unknown', message: info?.message ?? '' });
    stopLoop();
    // Drop the canvas configuration now, so a replacement renderer configures a clean context.
    target.release();
    options.onDeviceLost?.(deviceLost);
  });

  const readTarget = (): number | undefined => {
    const value = options.getTargetFrameTimeMs?.();
    return typeof value === 'number' && Number.isFinite(value) && value > 0 ? value : undefined;
  };

  const renderFrame = (timestamp: number): Promise<RendererFrameResult> => {
    assertUsable();
    const nextFrame = frame + 1;
    const active = xrActive;
    const frameProfile = profile();
    const frameId = (options.frameIdFactory ?? defaultFrameId)({ frame: nextFrame, xrActive: active, profile: frameProfile, timestamp });
    if (typeof frameId !== 'string' || frameId.length === 0) {
      throw new GpuRendererError('INVALID_OPTION', 'must return a non-empty string', { field: 'frameIdFactory' });
    }
    frame = nextFrame;
    const startedAt = rendererNow();
    const info: RendererFrameInfo = Object.freeze({ frame, frameId, timestamp, xrActive: active, profile: frameProfile, targetFrameTimeMs: readTarget() });
    options.onFrameStart?.(info);
    device.pushErrorScope('validation');
    let scope: Promise<GPUError | null>;
    try {
      encodeAndSubmitFrame({ device, target, format, size, clearColor, alpha, info, onBeforeEncode: options.onBeforeEncode });
    } finally {
      scope = device.popErrorScope();
    }
    lastFrameId = frameId;
    lastTimestamp = timestamp;
    options.onAfterSubmit?.(info);
    return Promise.all([scope, device.queue.onSubmittedWorkDone()]).then(([error]) => {
      if (error) throw new GpuRendererError('GPU_VALIDATION_FAILED', `frame ${frameId}: ${error.message}`);
      const result: RendererFrameResult = Object.freeze({ ...info, frameTimeMs: rendererNow() - startedAt });
      if (!destroyed) options.onFrameComplete?.(result);
      return result;
    });
  };

  const reportLoopError = (error: unknown): void => {
    stopLoop();
    if (options.onError) options.onError(error);
    else console.error('[gpu-renderer] frame failed; the loop stopped', error);
  };

  const tick = (timestamp: number): void => {
    frameHandle = undefined;
    if (!running) return;
    try {
      renderFrame(timestamp).catch(reportLoopError);
    } catch (error) {
      reportLoopError(error);
      return;
    }
    if (running) frameHandle = scheduler.request(tick);
  };

  const renderer: GpuRenderer = {
    device,
    format,
    resize(width, height, devicePixelRatio) {
      assertUsable();
      const dpr = devicePixelRatio ?? ((globalThis as { devicePixelRatio?: number }).devicePixelRatio || 1);
      const w = requireFiniteNumber(width, 'width');
      const h = requireFiniteNumber(height, 'height');
      requireFiniteNumber(dpr, 'devicePixelRatio');
      if (w <= 0) throw new GpuRendererError('INVALID_OPTION', `must be > 0, got ${w}`, { field: 'width' });
      if (h <= 0) throw new GpuRendererError('INVALID_OPTION', `must be > 0, got ${h}`, { field: 'height' });
      if (dpr <= 0) throw new GpuRendererError('INVALID_OPTION', `must be > 0, got ${dpr}`, { field: 'devicePixelRatio' });
      const pixelWidth = Math.max(1, Math.round(w * dpr));
      const pixelHeight = Math.max(1, Math.round(h * dpr));
      const limit = device.limits.maxTextureDimension2D;
      if (pixelWidth > limit) throw new GpuRendererError('INVALID_OPTION', `${pixelWidth} device pixels exceed maxTextureDimension2D ${limit}`, { field: 'width' });
      if (pixelHeight > limit) throw new GpuRendererError('INVALID_OPTION', `${pixelHeight} device pixels exceed maxTextureDimension2D ${limit}`, { field: 'height' });
      target.setSize(pixelWidth, pixelHeight);
      size = Object.freeze({ width: pixelWidth, height: pixelHeight, cssWidth: w, cssHeight: h, devicePixelRatio: dpr });
    },
    start() {
      assertUsable();
      if (running) return;
      running = true;
      frameHandle = scheduler.request(tick);
    },
    stop: stopLoop,
    renderOnce(timestamp) {
      try {
        return renderFrame(timestamp ?? rendererNow());
      } catch (error) {
        return Promise.reject(error);
      }
    },
    setClearColor(color) {
      clearColor = parseClearColor(color);
    },
    getSnapshot() {
      return Object.freeze({
        running,
        frame,
        lastFrameId,
        lastTimestamp,
        format,
        size,
        clearColor,
        xrActive,
        profile: profile(),
        workerManifest: getRendererWorkerManifest(profile()),
        deviceState,
        deviceLost,
        target: target.kind,
        destroyed,
      });
    },
    setXrActive(active) {
      if (destroyed) return;
      xrActive = Boolean(active);
    },
    bindXrManager(manager, bindingOptions) {
      assertUsable();
      unbindXr?.();
      const unbind = bindRendererToXrManager(renderer, manager, bindingOptions);
      unbindXr = unbind;
      return () => {
        unbind();
        if (unbindXr === unbind) unbindXr = undefined;
      };
    },
    async readPixels() {
      assertUsable();
      if (target.kind !== 'offscreen') {
        throw new GpuRendererError('INVALID_STATE', 'readPixels needs an offscreen target: presented canvas textures expire after presentation');
      }
      return readTexturePixels(device, target.getCurrentTexture(), format);
    },
    destroy() {
      if (destroyed) return;
      stopLoop();
      unbindXr?.();
      unbindXr = undefined;
      destroyed = true;
      if (deviceState === 'ready') deviceState = 'destroyed';
      target.release();
      if (ownsDevice) device.destroy();
    },
  };
  return renderer;
}
