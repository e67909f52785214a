import type { RendererWorkerManifest } from '../planning/worker-manifest-types.ts';
import type { RendererWorkerProfileName } from '../planning/worker-constants.ts';
import type { XrBindingOptions, XrManagerLike } from '../xr/xr-types.ts';
import type { RendererClearColorInput, RendererRgba } from './clear-color.ts';

/** Texture formats a WebGPU canvas may be configured with (WebGPU spec, GPUCanvasConfiguration). */
export type GpuRendererFormat = 'bgra8unorm' | 'rgba8unorm' | 'rgba16float';
export type GpuRendererCanvas = HTMLCanvasElement | OffscreenCanvas | string;
export type GpuRendererDeviceState = 'ready' | 'lost' | 'destroyed';

export interface GpuRendererSize {
  /** Target size in device pixels. */
  readonly width: number;
  readonly height: number;
  /** Size passed to `resize`, in CSS pixels. */
  readonly cssWidth: number;
  readonly cssHeight: number;
  readonly devicePixelRatio: number;
}

export interface RendererFrameIdInput {
  readonly frame: number;
  readonly xrActive: boolean;
  readonly profile: RendererWorkerProfileName;
  readonly timestamp: number;
}

export interface RendererFrameInfo {
  /** 1 for the first frame, +1 per frame. */
  readonly frame: number;
  readonly frameId: string;
  readonly timestamp: number;
  readonly xrActive: boolean;
  readonly profile: RendererWorkerProfileName;
  /** From `getTargetFrameTimeMs`, when given. */
  readonly targetFrameTimeMs: number | undefined;
}

/** What `onBeforeEncode` gets: the frame's encoder and its open render pass, already cleared. */
export interface RendererEncodeContext extends RendererFrameInfo {
  readonly device: GPUDevice;
  readonly encoder: GPUCommandEncoder;
  readonly pass: GPURenderPassEncoder;
  readonly texture: GPUTexture;
  readonly view: GPUTextureView;
  readonly format: GpuRendererFormat;
  readonly size: GpuRendererSize;
}

export interface RendererFrameResult extends RendererFrameInfo {
  /** Wall time from `onFrameStart` until the queue reported the frame's work done. */
  readonly frameTimeMs: number;
}

export interface RendererDeviceLostInfo {
  readonly reason: GPUDeviceLostReason | 'unknown';
  readonly message: string;
}

export interface GpuRendererOptions {
  /** Canvas element, OffscreenCanvas or CSS selector. Omit to render into an offscreen texture. */
  canvas?: GpuRendererCanvas;
  /** Size of the offscreen texture used when there is no canvas (default 300 x 150, a canvas's default). */
  target?: { width: number; height: number };
  clearColor?: RendererClearColorInput;
  powerPreference?: GPUPowerPreference;
  /** Default: the platform's preferred canvas format for canvases, rgba8unorm offscreen. */
  format?: GpuRendererFormat;
  /** Premultiplied-alpha presentation when true; opaque (alpha forced to 1) when false (default). */
  alpha?: boolean;
  /** Share a device; the renderer then never destroys it. */
  device?: GPUDevice;
  frameIdFactory?: (input: RendererFrameIdInput) => string;
  onFrameStart?: (info: RendererFrameInfo) => void;
  onBeforeEncode?: (context: RendererEncodeContext) => void;
  onAfterSubmit?: (info: RendererFrameInfo) => void;
  onFrameComplete?: (result: RendererFrameResult) => void;
  onDeviceLost?: (info: RendererDeviceLostInfo) => void;
  /** Errors thrown by frames of the `start()` loop (the loop stops); default logs them. */
  onError?: (error: unknown) => void;
  getTargetFrameTimeMs?: () => number | undefined;
  requestAnimationFrame?: (callback: (timestamp: number) => void) => unknown;
  cancelAnimationFrame?: (handle: unknown) => void;
}

export interface GpuRendererSnapshot {
  readonly running: boolean;
  /** Frames started so far. */
  readonly frame: number;
  readonly lastFrameId: string | undefined;
  readonly lastTimestamp: number | undefined;
  readonly format: GpuRendererFormat;
  readonly size: GpuRendererSize;
  readonly clearColor: RendererRgba;
  readonly xrActive: boolean;
  readonly profile: RendererWorkerProfileName;
  readonly workerManifest: RendererWorkerManifest;
  readonly deviceState: GpuRendererDeviceState;
  readonly deviceLost: RendererDeviceLostInfo | undefined;
  readonly target: 'canvas' | 'offscreen';
  readonly destroyed: boolean;
}

export interface RendererPixels {
  readonly width: number;
  readonly height: number;
  readonly format: GpuRendererFormat;
  /** Row-major, top row first, RGBA order: bytes for the 8-bit formats, floats for rgba16float. */
  readonly data: Uint8Array | Float32Array;
}

export interface GpuRenderer {
  readonly device: GPUDevice;
  readonly format: GpuRendererFormat;
  resize(width: number, height: number, devicePixelRatio?: number): void;
  start(): void;
  stop(): void;
  renderOnce(timestamp?: number): Promise<RendererFrameResult>;
  setClearColor(color: RendererClearColorInput): void;
  getSnapshot(): GpuRendererSnapshot;
  /** Switches the frame profile; called by the XR binding (see src/xr). */
  setXrActive(active: boolean): void;
  /** Binds an XR manager (replacing a previous binding); returns the unbind function. */
  bindXrManager(manager: XrManagerLike, options?: XrBindingOptions): () => void;
  /** Reads the offscreen target back (no canvas: presented canvas textures expire after presentation). */
  readPixels(): Promise<RendererPixels>;
  destroy(): void;
}
