import type { Document } from '@gltf-transform/core';
import type { AnimatedSceneCoreOptions } from '../../animation/animated-scene-core.ts';
import type { CameraTransform, CameraViewMode, HeadLookIntent } from '../../animation/camera/camera-types.ts';
import type { AnimatedCameraOptionsInput } from '../../animation/camera/camera-options.ts';
import type { AnimationSnapshotCore } from '../../animation/snapshot/animation-snapshot.ts';
import type { EnvironmentLightingInput } from '../../lighting/environment-lighting.ts';
import type { EnvironmentMapInput } from '../../lighting/environment-map.ts';
import type { GpuRendererCanvas, GpuRendererFormat, RendererPixels } from '../../runtime/renderer-types.ts';
import type { WavefrontPunctualLightInput, WavefrontSceneDescription, WavefrontToneMapping } from '../../scene/types.ts';
import type { RasterShadowOptions } from '../types.ts';

/**
 * Options of createAnimatedSceneRenderer (the 0.2 API's names, so its hosts keep working): the character
 * (`modelAsset`, a glTF Document or GLB bytes), its clips, beats, route, props and camera rig, plus
 * the raster renderer's output and lighting options.
 */
export interface AnimatedSceneRendererOptions extends Omit<AnimatedSceneCoreOptions, 'professional' | 'modelAsset'> {
  /** The skinned character: a @gltf-transform Document, or .glb bytes. */
  modelAsset: Document | Uint8Array | ArrayBuffer;
  /** Canvas element, OffscreenCanvas or selector; omit to render offscreen (`width` x `height`). */
  canvas?: GpuRendererCanvas;
  /** Default the canvas's size, else 640 x 360. */
  width?: number;
  height?: number;
  /** glTF documents drawn for props of a kind (grounded like primitive props); other kinds get built-in shapes. */
  propAssets?: Record<string, Document>;
  /** Draw the terrain under the route; default true. */
  ground?: boolean;
  /** Default: a soft uniform sky (0.35, 0.4, 0.5) with a shadow-casting key light. */
  environment?: { color: readonly number[] };
  environmentMap?: EnvironmentMapInput;
  environmentLighting?: EnvironmentLightingInput;
  /** KHR_lights_punctual lights; default one directional key light of 3 lux when no sky sun is given. */
  lights?: WavefrontPunctualLightInput[];
  toneMapping?: WavefrontToneMapping;
  exposure?: number;
  msaa?: 1 | 4;
  shadow?: RasterShadowOptions | false;
  format?: GpuRendererFormat;
  device?: GPUDevice;
  powerPreference?: GPUPowerPreference;
  /** Frame scheduling for `start()`; default the platform's requestAnimationFrame (a timer in Node). */
  requestAnimationFrame?: (callback: (timestamp: number) => void) => unknown;
  cancelAnimationFrame?: (handle: unknown) => void;
  /** Called after each frame of the `start()` loop; errors stop the loop and go to `onError`. */
  onFrame?: (snapshot: AnimatedSceneSnapshot) => void;
  onError?: (error: unknown) => void;
}

export type { AnimatedCameraOptionsInput };

/** Snapshot of the last rendered frame: the animation core's fields plus what the GPU draws. */
export interface AnimatedSceneSnapshot extends AnimationSnapshotCore {
  /** Every drawable primitive of the model was uploaded and is drawn (skinned on the GPU). */
  readonly modelRenderable: boolean;
  /** The active clip animates nodes of the drawn model. */
  readonly activeClipRenderable: boolean;
  /** The character's bounds intersect the view frustum. */
  readonly characterVisible: boolean;
  /** Projected conservative bounds of the posed character in pixels (x0, y0, x1, y1), or null when it reaches behind the camera. */
  readonly characterScreenBounds: readonly [number, number, number, number] | null;
  readonly renderMode: 'webgpu-pbr';
  /** GPU textures the scene samples, and how many the character's materials bind. */
  readonly textureCount: number;
  readonly characterTextureCount: number;
  /** Every skinned primitive's material has a normal texture, which the shader applies. */
  readonly normalMapReady: boolean;
  /**
   * What moves the character in the active beat: 'authored-travel' (travel/jump beat, distance from
   * the clip's authored root motion, along the route), 'route-driven' (travel beat with an in-place
   * clip), 'authored' (stationary beat keeping the clip's root translation), 'in-place' (holding).
   */
  readonly rootMotionPolicy: 'authored-travel' | 'route-driven' | 'authored' | 'in-place';
  readonly drawCalls: number;
  readonly frameTimeMs: number;
  readonly running: boolean;
  readonly size: { readonly width: number; readonly height: number };
}

export interface AnimatedSceneRenderer {
  readonly device: GPUDevice;
  /** Starts the requestAnimationFrame loop (scene time = time since start). */
  start(): void;
  stop(): void;
  resize(width: number, height: number): void;
  /** Renders scene time `tMs` (default: the loop's clock, 0 before start) and returns its snapshot. */
  renderOnce(tMs?: number): Promise<AnimatedSceneSnapshot>;
  getSnapshot(): AnimatedSceneSnapshot | null;
  setCamera(options: AnimatedCameraOptionsInput): void;
  setCameraViewMode(mode: CameraViewMode): void;
  applyCameraControl(control: unknown): void;
  /** The offscreen output as RGBA8 (no canvas). */
  readPixels(): Promise<RendererPixels>;
  /**
   * The posed scene at `tMs` for the path tracer: skinned vertices baked on the CPU, props and
   * ground, the rig's camera, and the lighting the raster view draws (the same environment colour,
   * map or sky and the same lights, the default key light included). Spread it into
   * createWavefrontPathTracingComputeRenderer's options; its BVH is built from these meshes.
   */
  posedScene(tMs: number): AnimatedPosedScene;
  destroy(): void;
}

/** A posed still for the path tracer: the scene plus the raster view's lighting. */
export interface AnimatedPosedScene extends Omit<WavefrontSceneDescription, 'lights'> {
  lights: WavefrontPunctualLightInput[];
  environmentMap?: EnvironmentMapInput;
  environmentLighting?: EnvironmentLightingInput;
}

export type { CameraTransform, HeadLookIntent };
