/**
 * Sequences of a loaded glTF scene: frames of its animation (frame f posed at f / fps), turntable
 * orbits and KHR_materials_variants, in any combination. The plan is data (what each frame is and
 * where it goes), so a caller can skip frames already rendered before posing anything; posing a
 * frame reuses the loaded asset (`GltfScene.pose`), never reading it again.
 */
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import type { GltfScene } from '../io/gltf/gltf-scene-reader.ts';
import type { WavefrontCameraInput, WavefrontSceneDescription } from '../scene/types.ts';
import { checkFrameNumbers } from './frame-list.ts';
import type { OutputPatternValues } from './output-pattern.ts';
import { checkTurntable, turntableCamera, type TurntableOptions } from './turntable.ts';

export interface GltfSequenceOptions {
  /** Frame numbers, each posing the animation at frame / fps. Default: the turntable's frames 0..n-1, else frame 0. */
  frames?: readonly number[];
  /** Frames per second of `frames`; default 24. */
  fps?: number;
  /** The animation (index or name; null none); default the scene's. */
  animation?: number | string | null;
  /** The pose time of every frame of a sequence without `frames` (a turntable, variants of a still); default the scene's. */
  time?: number;
  /** Orbit the model: frames per revolution, or the orbit's options. With `frames`, frame f looks from 360 f / n degrees. */
  turntable?: number | TurntableOptions;
  /** KHR_materials_variants to render, each as its own pass over the frames: 'all' or names. */
  variants?: 'all' | readonly string[];
  /** glTF cameras to render from, each as its own pass over the frames: 'all', or camera names or indices. */
  cameras?: 'all' | readonly (string | number)[];
  /** Image width / height, for the turntable's framing; default 1. */
  aspect?: number;
}

/** One frame of a sequence plan. */
export interface GltfSequenceItem {
  /** Position in the sequence, from 0. */
  index: number;
  /** The frame number (what output patterns print). */
  frame: number;
  /** Seconds into the animation. */
  time: number;
  /** The variant shown; undefined for the default materials. */
  variant: string | undefined;
  /** The glTF camera (index `/cameras/i`) of a pass over `cameras`; undefined: the scene's camera choice. */
  cameraIndex: number | undefined;
  /** That camera's name (what output patterns print as {camera}). */
  cameraName: string | undefined;
  /** The turntable camera, when orbiting. */
  turntableCamera: WavefrontCameraInput | undefined;
}

/** A posed frame: `options` are the renderer's scene options (spread them into the renderer or `updateScene`). */
export interface GltfSequenceFrame extends GltfSequenceItem {
  scene: GltfScene;
  options: WavefrontSceneDescription;
}

function invalid(field: string, message: string): never {
  throw new GpuRendererError('INVALID_OPTION', message, { field });
}

function chooseVariants(scene: GltfScene, variants: GltfSequenceOptions['variants']): (string | undefined)[] {
  if (variants === undefined) return [scene.variant];
  if (scene.variants.length === 0) invalid('variants', 'the asset has no KHR_materials_variants variants');
  if (variants === 'all') return [...scene.variants];
  if (!Array.isArray(variants) || variants.length === 0) invalid('variants', "expected 'all' or a non-empty list of variant names");
  const seen = new Set<string>();
  return variants.map((name, i) => {
    if (!scene.variants.includes(name)) invalid(`variants[${i}]`, `no variant ${JSON.stringify(name)} (the asset has ${scene.variants.map((v) => JSON.stringify(v)).join(', ')})`);
    if (seen.has(name)) invalid(`variants[${i}]`, `variant ${JSON.stringify(name)} is listed twice`);
    seen.add(name);
    return name;
  });
}

function chooseCameras(scene: GltfScene, cameras: GltfSequenceOptions['cameras']): { index: number | undefined; name: string | undefined }[] {
  if (cameras === undefined) return [{ index: undefined, name: undefined }];
  if (scene.cameras.length === 0) invalid('cameras', 'the asset places no cameras');
  if (cameras === 'all') return scene.cameras.map((c) => ({ index: c.cameraIndex, name: c.name }));
  if (!Array.isArray(cameras) || cameras.length === 0) invalid('cameras', "expected 'all' or a non-empty list of camera names or indices");
  const seen = new Set<number>();
  return cameras.map((choice, i) => {
    const found = typeof choice === 'number' ? scene.cameras.find((c) => c.cameraIndex === choice) : (scene.cameras.find((c) => c.nodeName === choice) ?? scene.cameras.find((c) => c.name === choice));
    if (found === undefined) invalid(`cameras[${i}]`, `no camera ${JSON.stringify(choice)} (cameras: ${scene.cameras.map((c) => `${c.cameraIndex} ${JSON.stringify(c.name)}`).join(', ')})`);
    if (seen.has(found.cameraIndex)) invalid(`cameras[${i}]`, `camera ${JSON.stringify(choice)} is listed twice`);
    seen.add(found.cameraIndex);
    return { index: found.cameraIndex, name: found.name };
  });
}

/** The frames of a sequence, in render order (variant by variant, camera by camera, frames in the order given). */
export function planGltfSequence(scene: GltfScene, options: GltfSequenceOptions = {}): GltfSequenceItem[] {
  const fps = options.fps ?? 24;
  if (typeof fps !== 'number' || !Number.isFinite(fps) || fps <= 0) invalid('fps', `expected frames per second > 0, got ${String(fps)}`);
  const aspect = options.aspect ?? 1;
  if (!Number.isFinite(aspect) || aspect <= 0) invalid('aspect', `expected width / height > 0, got ${aspect}`);
  const turntable = options.turntable === undefined ? undefined : checkTurntable(typeof options.turntable === 'number' ? { frames: options.turntable } : options.turntable);
  const frames = options.frames !== undefined ? checkFrameNumbers(options.frames) : turntable !== undefined ? Array.from({ length: turntable.frames }, (_, i) => i) : [0];
  const stillTime = options.time ?? scene.time;
  if (options.frames !== undefined && options.time !== undefined) invalid('time', 'a sequence with frames poses frame f at f / fps; leave time out');
  if (!Number.isFinite(stillTime) || stillTime < 0) invalid('time', `expected seconds >= 0, got ${stillTime}`);
  const variants = chooseVariants(scene, options.variants);
  if (options.cameras !== undefined && turntable !== undefined) invalid('cameras', 'a turntable brings its own camera; give cameras or turntable');
  const cameras = chooseCameras(scene, options.cameras);
  const items: GltfSequenceItem[] = [];
  for (const variant of variants) {
    for (const camera of cameras) {
      for (const frame of frames) {
        items.push({
          index: items.length,
          frame,
          time: options.frames !== undefined ? frame / fps : stillTime,
          variant,
          cameraIndex: camera.index,
          cameraName: camera.name,
          turntableCamera: turntable === undefined ? undefined : turntableCamera(scene.bounds, frame, turntable, aspect),
        });
      }
    }
  }
  return items;
}

/** Poses one planned frame (the animation of `options`, else the scene's). */
export async function poseGltfSequenceItem(scene: GltfScene, item: GltfSequenceItem, options: Pick<GltfSequenceOptions, 'animation'> = {}): Promise<GltfSequenceFrame> {
  const posed = await scene.pose({
    time: item.time,
    ...(item.variant !== undefined ? { variant: item.variant } : {}),
    ...(item.cameraIndex !== undefined ? { camera: item.cameraIndex } : {}),
    ...(options.animation !== undefined ? { animation: options.animation } : {}),
  });
  return { ...item, scene: posed, options: { ...posed, camera: item.turntableCamera ?? posed.camera } };
}

/** Plans and poses a sequence frame by frame. */
export async function* gltfSequence(scene: GltfScene, options: GltfSequenceOptions = {}): AsyncGenerator<GltfSequenceFrame> {
  for (const item of planGltfSequence(scene, options)) yield poseGltfSequenceItem(scene, item, options);
}

/** The output pattern values of planned items (frame number, variant and camera names). */
export function sequencePatternValues(items: readonly GltfSequenceItem[]): OutputPatternValues[] {
  return items.map((item) => ({ frame: item.frame, variant: item.variant, camera: item.cameraName }));
}
