/**
 * What the command line asks for, as the parsers (render-args.ts, farm-args.ts) produce it and the
 * commands (render-command.ts, sequence-command.ts, farm-command.ts) run it: the types both sides
 * share, below either.
 */
import type { WavefrontAovName } from '../film/aovs.ts';
import type { ImageFileFormat } from '../io/images/image-file.ts';
import type { WavefrontToneMapping } from '../scene/types.ts';

export interface RenderCommand {
  kind: 'render';
  /** Scene file: JSON, or glTF 2.0 (.glb / .gltf); undefined renders the built-in Cornell box. */
  scenePath: string | undefined;
  /** glTF scenes: the camera to render from, by name (default the scene's first camera). */
  camera?: string;
  /** glTF scenes: the KHR_materials_variants variant to render. */
  variant?: string;
  width: number;
  height: number;
  /** Target samples per pixel. */
  spp: number;
  /** Samples per pixel per renderFrame call (progress granularity). */
  sppPerFrame: number;
  maxDepth: number;
  seed: number;
  toneMapping: WavefrontToneMapping;
  exposure: number;
  /** Exposure in stops, multiplying `exposure` by 2^exposureEv (display only). */
  exposureEv: number;
  out: string;
  /** Output format, from the extension of `out`. */
  format: ImageFileFormat;
  /** Stop after this many milliseconds (--time); spp stays the ceiling. */
  timeLimitMs?: number;
  /** Adaptive sampling's noise threshold (--noise); spp stays the ceiling. */
  noiseThreshold?: number;
  /** Adaptive sampling's per-pixel minimum (--min-spp). */
  minSpp?: number;
  /** AOV layers written into an .exr output (--aov). */
  aovs: WavefrontAovName[];
  /**
   * Denoise the image (--denoise [oidn|atrous]): true picks the better denoiser the device runs
   * (OIDN); an .exr keeps the raw beauty as layer raw.R/G/B.
   */
  denoise: boolean | 'oidn' | 'atrous';
  /** OpenEXR pixel type (--half: half floats, else float). */
  half: boolean;
  /** Multiple-scattering energy compensation on rough microfacets (off with --no-energy-compensation). */
  energyCompensation: boolean;
  /** Environment map file (.hdr or .exr) lighting the scene (`--env`). */
  env?: string;
  /** Multiplies the environment map's radiance (`--env-intensity`). */
  envIntensity?: number;
  /** Rotation of the environment map about +Y in degrees (`--env-rotation`). */
  envRotationDegrees?: number;
  /** glTF: the animation to pose, by name, else by index (`--animation`). */
  animation?: string;
  /** glTF: seconds into the animation for a still or a turntable (`--at`). */
  at?: number;
  /** Sequence: frame numbers, each posed at frame / fps (`--frames`). */
  frames?: number[];
  /** Frames per second of `frames` (`--fps`); default 24. */
  fps?: number;
  /** Sequence: frames per orbit of the framed model (`--turntable`). */
  turntable?: number;
  /** Sequence: KHR_materials_variants to render, one image each (`--variants all|a,b`). */
  variants?: 'all' | string[];
  /** Sequence: glTF cameras to render from, one pass each (`--cameras all|a,b`). */
  cameras?: 'all' | string[];
  /** Sequence: render frames whose file exists too (`--overwrite`); default they are skipped. */
  overwrite?: boolean;
  /** Negative texels of an environment map file (lossy EXR ringing): set to 0 and reported, or refused. */
  negativeTexels: 'zero' | 'error';
  /** Eye position (`--camera-position x,y,z`); replaces the scene's camera. */
  cameraPosition?: [number, number, number];
  /** Look-at point (`--camera-target x,y,z`, with --camera-position); default the scene bounds' centre. */
  cameraTarget?: [number, number, number];
  /** Orbit of the scene bounds' centre (`--orbit azimuth,elevation[,distance]`, degrees); replaces the scene's camera. */
  orbit?: { azimuthDegrees: number; elevationDegrees: number; distance?: number };
  /** Vertical field of view in degrees (`--fov`) of the camera rendered from. */
  fovYDegrees?: number;
  /** Where the BVH is built (`--bvh-build`): 'cpu-upload' (the renderer's default) or 'gpu'. */
  accelerationBuildMode?: 'cpu-upload' | 'gpu';
  /** The path tracer's integrator (`--integrator`): 'wavefront' (the renderer's default) or 'megakernel'. */
  integrator?: 'wavefront' | 'megakernel';
  /** Shared meshes through bottom-level trees (`--instancing`): 'auto' (the renderer's default), 'off' or 'always'. */
  instancing?: 'auto' | 'off' | 'always';
  /** Origins the scene's references may be fetched from (`--allow-origin`, repeatable); default none. */
  allowedOrigins?: string[];
}

export interface HelpCommand {
  kind: 'help';
  text: string;
}

export interface FarmCommandBase {
  kind: 'farm';
  redis?: string;
  queue?: string;
}

export interface FarmSubmitCommand extends FarmCommandBase {
  action: 'submit';
  /** The render command (command line), or undefined with `jobFile`. */
  render?: RenderCommand;
  jobFile?: string;
  name?: string;
  attempts?: number;
  backoffMs?: number;
}

export interface FarmWorkerCommand extends FarmCommandBase {
  action: 'worker';
  exitWhenIdle: boolean;
  lockDuration?: number;
  stalledInterval?: number;
  /** Folders frames may be written into (`--output-root`, repeatable). */
  outputRoots?: string[];
  /** Folders assets and what they reference may be read from (`--asset-root`, repeatable). */
  assetRoots?: string[];
  /** Job path prefixes replaced on this worker (`--path-map FROM=TO`, repeatable). */
  pathMap?: { from: string; to: string }[];
  /** Origins an asset's references may be fetched from (`--allow-origin`, repeatable). */
  allowedOrigins?: string[];
}

export interface FarmStatusCommand extends FarmCommandBase {
  action: 'status';
  job?: string;
  json: boolean;
  wait: boolean;
  timeoutSeconds?: number;
}

export type FarmCommand = FarmSubmitCommand | FarmWorkerCommand | FarmStatusCommand;

export type CliCommand = RenderCommand | HelpCommand | FarmCommand;
