/** Command-line parsing for `gpu-renderer`, kept free of I/O so it is testable in isolation. */
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import type { WavefrontAovName } from '../film/aovs.ts';
import { imageFileFormatFromPath, type ImageFileFormat } from '../io/images/image-file.ts';
import { parseAovList, parseDuration } from '../film/option-parsing.ts';
import { parseOrigin } from '../io/resource-policy.ts';
import type { WavefrontToneMapping } from '../scene/types.ts';
import { parseFrameList } from '../sequence/frame-list.ts';
import { parseFarmArgs, type FarmCommand } from './farm-args.ts';
import { hasCameraPlaceholder, hasFramePlaceholder, hasVariantPlaceholder } from '../sequence/output-pattern.ts';

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
  /** Origins the scene's references may be fetched from (`--allow-origin`, repeatable); default none. */
  allowedOrigins?: string[];
}

export interface HelpCommand {
  kind: 'help';
  text: string;
}

export type CliCommand = RenderCommand | HelpCommand | FarmCommand;

export const renderDefaults = {
  width: 512,
  height: 512,
  spp: 64,
  sppPerFrame: 4,
  maxDepth: 8,
  seed: 0,
  toneMapping: 'neutral',
  exposure: 1,
  exposureEv: 0,
  out: 'render.png',
  format: 'png',
  denoise: false,
  half: false,
  energyCompensation: true,
  negativeTexels: 'zero',
} as const satisfies Omit<RenderCommand, 'kind' | 'scenePath' | 'aovs'>;

export const usage = `Usage: gpu-renderer render [scene.json | model.glb | model.gltf] [options]
       gpu-renderer farm <submit | worker | status> [options]   (see gpu-renderer farm --help)

Renders a scene with the WebGPU wavefront path tracer and writes a PNG, OpenEXR or Radiance HDR
image (by the extension of --out). The scene is a scene JSON file or a glTF 2.0 asset (.glb or
.gltf, chosen by extension). Without a scene file it renders the built-in Cornell box.

Options:
  --width <px>             image width (default ${renderDefaults.width})
  --height <px>            image height (default ${renderDefaults.height})
  --spp <n>                samples per pixel; the ceiling with --time or --noise (default ${renderDefaults.spp})
  --time <duration>        stop after this long, e.g. 30s, 2m, 1m30s (the progress bar counts down)
  --noise <threshold>      adaptive sampling: pixels stop once their noise estimate is below this
                           (Cycles' noise threshold, e.g. 0.01); the render ends when all have
  --min-spp <n>            with --noise: samples every pixel takes first (default: Cycles' rule,
                           at most spp / 4)
  --spp-per-frame <n>      samples per pixel per GPU frame (default ${renderDefaults.sppPerFrame})
  --max-depth <n>          scattering events per path, 1..32 (default ${renderDefaults.maxDepth})
  --seed <n>               sampler seed, 0..4294967295 (default ${renderDefaults.seed})
  --tone-mapping <mode>    neutral | aces | agx | linear (default ${renderDefaults.toneMapping})
  --exposure <x>           radiance multiplier before tone mapping (default ${renderDefaults.exposure})
  --exposure-ev <stops>    exposure in stops, multiplying --exposure by 2^stops (default 0)
  --out <file>             output image: .png (tone mapped), .exr or .hdr (linear radiance,
                           exposure and tone mapping do not apply) (default ${renderDefaults.out})
  --aov <list>             .exr only: AOV layers, comma separated: albedo, normal, depth, emission,
                           objectId, materialId, variance, sampleCount
  --denoise [oidn|atrous]  denoise on the GPU: oidn (Open Image Denoise's network, the default) or
                           atrous (the fast edge-avoiding a-trous preview); an .exr keeps the raw
                           beauty as layer raw.R/G/B
  --half                   .exr only: half-float channels (ids and counts stay float)
  --no-energy-compensation render rough microfacets single-scattering only (the glTF Appendix B
                           model as specified), without the multiple-scattering energy compensation
  --env <file>             environment map lighting the scene: Radiance .hdr or OpenEXR,
                           equirectangular, top row = +Y (replaces the scene's environment)
  --env-intensity <x>      multiplies the environment map's radiance (default 1)
  --env-rotation <deg>     rotates the environment map about +Y (default 0)
  --negative-texels <m>    environment map texels below zero (the ringing of lossy EXR
                           compression, e.g. the HDRIs of @pmndrs/assets): zero (set them to 0
                           and report how many and how much energy that adds) | error (refuse
                           the map) (default ${renderDefaults.negativeTexels}); --env also takes those
                           packages' .exr.js modules (a default-exported data: URL)
  --camera <name>          glTF: render from the camera (node or camera) of that name
                           (default the scene's first camera, else a raised three-quarter view
                           framing the scene bounds: azimuth 30, elevation 25, fov 45)
  --orbit <az,el[,dist]>   camera on an orbit of the scene bounds' centre: azimuth in degrees
                           about +Y from +Z towards +X, elevation in degrees (-90..90) and
                           distance (default: the nearest at which the bounds fit the image)
  --camera-position <x,y,z> camera eye position (replaces the scene's camera)
  --camera-target <x,y,z>  with --camera-position: the point looked at (default the centre of
                           the scene bounds)
  --fov <deg>              vertical field of view of the camera rendered from, in (0, 179]
  --variant <name>         glTF: KHR_materials_variants variant to render
  --animation <name|i>     glTF: the animation to pose, by name or index (default the first)
  --at <seconds>           glTF: pose the animation at this time (default 0)

Sequences (glTF; --out holds #### for the frame number, {variant} and {camera} for names):
  --frames <list>          frames to render, e.g. 0-23, 0-239:10, 1,5,9; frame f poses the
                           animation at f / fps
  --fps <n>                frames per second of --frames (default 24)
  --turntable <n>          orbit the framed model in n frames (with --frames: frame f looks from
                           360 f / n degrees)
  --variants <all|a,b>     one image per KHR_materials_variants variant
  --cameras <all|a,b>      one image per glTF camera (by name; {camera} in --out)
  --overwrite              render frames whose file exists (default: skip them, so an
                           interrupted sequence resumes)
  --bvh-build <where>      cpu-upload (binned SAH on the CPU, the default) | gpu (LBVH built on the
                           GPU: faster to build on a real GPU, its tree ~25-30 % costlier (SAH))
  --integrator <form>      wavefront (queued stages per bounce, the default) | megakernel (one
                           kernel runs each path through all its bounces; same image)
  --allow-origin <origin>  let the scene's references fetch from this origin (e.g.
                           https://cdn.example.com; repeatable or comma separated). By default a
                           scene reads only files in its own folder and makes no network request
  -h, --help               show this help
`;

function invalid(field: string, message: string): never {
  throw new GpuRendererError('INVALID_OPTION', message, { field });
}

function integer(flag: string, text: string, min: number, max: number): number {
  if (!/^[+]?\d+$/.test(text)) invalid(flag, `expected an integer, got ${JSON.stringify(text)}`);
  const n = Number(text);
  if (n < min || n > max) invalid(flag, `must be between ${min} and ${max}, got ${n}`);
  return n;
}

function finiteNumber(flag: string, text: string, min = -Infinity): number {
  const n = text.trim() === '' ? Number.NaN : Number(text);
  if (!Number.isFinite(n) || n < min) invalid(flag, `expected a finite number${min > -Infinity ? ` >= ${min}` : ''}, got ${JSON.stringify(text)}`);
  return n;
}

function positiveNumber(flag: string, text: string): number {
  const n = text.trim() === '' ? Number.NaN : Number(text);
  if (!Number.isFinite(n) || n <= 0) invalid(flag, `expected a finite number > 0, got ${JSON.stringify(text)}`);
  return n;
}

/** A command that renders a sequence of images (frames, a turntable or variants) rather than one still. */
export function isSequence(command: Pick<RenderCommand, 'frames' | 'turntable' | 'variants' | 'cameras'>): boolean {
  return command.frames !== undefined || command.turntable !== undefined || command.variants !== undefined || command.cameras !== undefined;
}

/** `x,y,z`: three finite numbers separated by commas. */
function vector3(flag: string, text: string): [number, number, number] {
  const parts = text.split(',');
  const values = parts.map((p) => (p.trim() === '' ? Number.NaN : Number(p)));
  if (values.length !== 3 || !values.every(Number.isFinite)) invalid(flag, `expected x,y,z (three finite numbers), got ${JSON.stringify(text)}`);
  return values as [number, number, number];
}

/** `azimuth,elevation[,distance]` in degrees and scene units. */
function orbit(flag: string, text: string): NonNullable<RenderCommand['orbit']> {
  const values = text.split(',').map((p) => (p.trim() === '' ? Number.NaN : Number(p)));
  if ((values.length !== 2 && values.length !== 3) || !values.every(Number.isFinite)) {
    invalid(flag, `expected azimuth,elevation or azimuth,elevation,distance (finite numbers), got ${JSON.stringify(text)}`);
  }
  const [azimuthDegrees, elevationDegrees, distance] = values as [number, number, number | undefined];
  if (Math.abs(elevationDegrees) > 90) invalid(flag, `elevation must be within [-90, 90] degrees, got ${elevationDegrees}`);
  if (distance !== undefined && !(distance > 0)) invalid(flag, `distance must be > 0, got ${distance}`);
  return { azimuthDegrees, elevationDegrees, ...(distance !== undefined ? { distance } : {}) };
}

/** True for paths the CLI loads as glTF 2.0 (.glb, .gltf; case-insensitive). */
export function isGltfPath(path: string): boolean {
  return /\.(glb|gltf)$/i.test(path);
}

/** Parses the arguments after `render` (e.g. `['scene.json', '--spp', '16']`). */
export function parseRenderArgs(argv: readonly string[]): RenderCommand | HelpCommand {
  const command: RenderCommand = { kind: 'render', scenePath: undefined, ...renderDefaults, aovs: [] };
  let sppPerFrameGiven = false;
  for (let i = 0; i < argv.length; i++) {
    const arg = argv[i];
    if (arg === '-h' || arg === '--help') return { kind: 'help', text: usage };
    if (!arg.startsWith('-') || arg === '-') {
      if (command.scenePath !== undefined) invalid('scene', `only one scene file may be given (got ${JSON.stringify(command.scenePath)} and ${JSON.stringify(arg)})`);
      command.scenePath = arg;
      continue;
    }
    if (arg === '--') {
      // Everything after `--` is positional.
      for (const rest of argv.slice(i + 1)) {
        if (command.scenePath !== undefined) invalid('scene', `only one scene file may be given (got ${JSON.stringify(command.scenePath)} and ${JSON.stringify(rest)})`);
        command.scenePath = rest;
      }
      break;
    }
    const eq = arg.indexOf('=');
    const flag = eq >= 0 ? arg.slice(0, eq) : arg;
    let value: string | undefined = eq >= 0 ? arg.slice(eq + 1) : undefined;
    const take = (): string => {
      if (value === undefined) {
        const next = argv[i + 1];
        if (next === undefined || (next.startsWith('--') && next.length > 2)) invalid(flag, 'expects a value');
        i++;
        value = next;
      }
      return value;
    };
    switch (flag) {
      case '--width':
        command.width = integer(flag, take(), 1, 16384);
        break;
      case '--height':
        command.height = integer(flag, take(), 1, 16384);
        break;
      case '--spp':
        command.spp = integer(flag, take(), 1, 1 << 20);
        break;
      case '--spp-per-frame':
        command.sppPerFrame = integer(flag, take(), 1, 1024);
        sppPerFrameGiven = true;
        break;
      case '--max-depth':
        command.maxDepth = integer(flag, take(), 1, 32);
        break;
      case '--seed':
        command.seed = integer(flag, take(), 0, 0xffffffff);
        break;
      case '--tone-mapping': {
        const mode = take();
        if (mode !== 'neutral' && mode !== 'aces' && mode !== 'agx' && mode !== 'linear') invalid(flag, `expected neutral, aces, agx or linear, got ${JSON.stringify(mode)}`);
        command.toneMapping = mode;
        break;
      }
      case '--exposure':
        command.exposure = positiveNumber(flag, take());
        break;
      case '--exposure-ev': {
        const text = take();
        const ev = text.trim() === '' ? Number.NaN : Number(text);
        if (!Number.isFinite(ev) || Math.abs(ev) > 64) invalid(flag, `expected a number of stops in [-64, 64], got ${JSON.stringify(text)}`);
        command.exposureEv = ev;
        break;
      }
      case '--time':
        command.timeLimitMs = parseDuration(take(), flag);
        break;
      case '--noise':
        command.noiseThreshold = positiveNumber(flag, take());
        break;
      case '--min-spp':
        command.minSpp = integer(flag, take(), 2, 65536);
        break;
      case '--aov':
        command.aovs = parseAovList(take(), flag);
        break;
      case '--denoise': {
        // The value is optional: `--denoise=x`, or a following `oidn` / `atrous` (never a scene path).
        const next = argv[i + 1];
        if (value === undefined && (next === 'oidn' || next === 'atrous')) value = argv[++i];
        if (value !== undefined && value !== 'oidn' && value !== 'atrous') invalid(flag, `expected oidn or atrous, got ${JSON.stringify(value)}`);
        command.denoise = value === undefined ? true : (value as 'oidn' | 'atrous');
        break;
      }
      case '--half':
        if (value !== undefined) invalid(flag, 'takes no value');
        command.half = true;
        break;
      case '--no-energy-compensation':
        if (value !== undefined) invalid(flag, 'takes no value');
        command.energyCompensation = false;
        break;
      case '--camera':
      case '--variant': {
        const name = take();
        if (name === '') invalid(flag, 'expects a name');
        command[flag === '--camera' ? 'camera' : 'variant'] = name;
        break;
      }
      case '--out': {
        const out = take();
        if (out === '') invalid(flag, 'expects a file name');
        command.out = out;
        break;
      }
      case '--env': {
        const env = take();
        if (env === '') invalid(flag, 'expects a file name');
        command.env = env;
        break;
      }
      case '--bvh-build': {
        const where = take();
        if (where !== 'cpu-upload' && where !== 'gpu') invalid(flag, `expected cpu-upload or gpu, got ${JSON.stringify(where)}`);
        command.accelerationBuildMode = where;
        break;
      }
      case '--integrator': {
        const form = take();
        if (form !== 'wavefront' && form !== 'megakernel') invalid(flag, `expected wavefront or megakernel, got ${JSON.stringify(form)}`);
        command.integrator = form;
        break;
      }
      case '--env-intensity':
        command.envIntensity = finiteNumber(flag, take(), 0);
        break;
      case '--env-rotation':
        command.envRotationDegrees = finiteNumber(flag, take());
        break;
      case '--animation': {
        const name = take();
        if (name === '') invalid(flag, 'expects an animation name or index');
        command.animation = name;
        break;
      }
      case '--at':
        command.at = finiteNumber(flag, take(), 0);
        break;
      case '--frames':
        command.frames = parseFrameList(take(), flag);
        break;
      case '--fps':
        command.fps = positiveNumber(flag, take());
        break;
      case '--turntable':
        command.turntable = integer(flag, take(), 1, 100000);
        break;
      case '--variants':
      case '--cameras': {
        const list = take();
        let names: 'all' | string[] = 'all';
        if (list !== 'all') {
          names = list.split(',').map((n) => n.trim());
          if (names.some((n) => n === '')) invalid(flag, `expected all or comma-separated names, got ${JSON.stringify(list)}`);
        }
        command[flag === '--variants' ? 'variants' : 'cameras'] = names;
        break;
      }
      case '--overwrite':
        if (value !== undefined) invalid(flag, 'takes no value');
        command.overwrite = true;
        break;
      case '--negative-texels': {
        const mode = take();
        if (mode !== 'zero' && mode !== 'error') invalid(flag, `expected zero or error, got ${JSON.stringify(mode)}`);
        command.negativeTexels = mode;
        break;
      }
      case '--camera-position':
        command.cameraPosition = vector3(flag, take());
        break;
      case '--camera-target':
        command.cameraTarget = vector3(flag, take());
        break;
      case '--orbit':
        command.orbit = orbit(flag, take());
        break;
      case '--fov': {
        const text = take();
        const fov = text.trim() === '' ? Number.NaN : Number(text);
        if (!(fov > 0 && fov <= 179)) invalid(flag, `expected degrees in (0, 179], got ${JSON.stringify(text)}`);
        command.fovYDegrees = fov;
        break;
      }
      case '--allow-origin':
        for (const origin of take().split(',')) (command.allowedOrigins ??= []).push(parseOrigin(origin.trim(), flag));
        break;
      default:
        invalid(flag, `unknown option (see --help)`);
    }
  }
  if (!sppPerFrameGiven) command.sppPerFrame = Math.min(command.sppPerFrame, command.spp);
  try {
    command.format = imageFileFormatFromPath(command.out);
  } catch {
    invalid('--out', `cannot tell the image format from ${JSON.stringify(command.out)} (expected .png, .exr or .hdr)`);
  }
  if (command.aovs.length > 0 && command.format !== 'exr') invalid('--aov', 'AOV layers need an .exr output');
  if (command.half && command.format !== 'exr') invalid('--half', 'applies to .exr output only');
  if (command.minSpp !== undefined && command.noiseThreshold === undefined) invalid('--min-spp', 'applies with --noise');
  if (command.minSpp !== undefined && command.minSpp > command.spp) invalid('--min-spp', `must be <= --spp (${command.spp})`);
  if (command.cameraTarget !== undefined && command.cameraPosition === undefined) invalid('--camera-target', 'needs --camera-position (or use --orbit)');
  if (command.orbit !== undefined && command.cameraPosition !== undefined) invalid('--orbit', 'cannot be combined with --camera-position');
  if (command.camera !== undefined && (command.orbit !== undefined || command.cameraPosition !== undefined)) {
    invalid('--camera', `names a camera of the asset; ${command.orbit !== undefined ? '--orbit' : '--camera-position'} places one instead`);
  }
  const gltfOnly = [['--camera', command.camera], ['--variant', command.variant], ['--animation', command.animation], ['--at', command.at], ['--frames', command.frames], ['--turntable', command.turntable], ['--variants', command.variants], ['--cameras', command.cameras]] as const;
  for (const [flag, value] of gltfOnly) {
    if (value !== undefined && (command.scenePath === undefined || !isGltfPath(command.scenePath))) invalid(flag, 'applies to glTF scenes (.glb or .gltf) only');
  }
  if (command.at !== undefined && command.frames !== undefined) invalid('--at', '--frames pose frame f at f / fps; give one of --at and --frames');
  if (command.fps !== undefined && command.frames === undefined) invalid('--fps', 'applies with --frames');
  if (command.variant !== undefined && command.variants !== undefined) invalid('--variants', 'give one of --variant and --variants');
  if (command.camera !== undefined && command.cameras !== undefined) invalid('--cameras', 'give one of --camera and --cameras');
  if (command.turntable !== undefined && command.cameras !== undefined) invalid('--cameras', 'a turntable brings its own camera; give one of --turntable and --cameras');
  const placed = command.orbit !== undefined ? '--orbit' : command.cameraPosition !== undefined ? '--camera-position' : undefined;
  if (placed !== undefined && command.turntable !== undefined) invalid('--turntable', `a turntable brings its own camera; give one of --turntable and ${placed}`);
  if (placed !== undefined && command.cameras !== undefined) invalid('--cameras', `give one of --cameras and ${placed}`);
  if (command.overwrite === true && !isSequence(command)) invalid('--overwrite', 'applies to sequences (--frames, --turntable, --variants, --cameras)');
  if (isSequence(command)) {
    const frameCount = command.frames?.length ?? command.turntable ?? 1;
    if (frameCount > 1 && !hasFramePlaceholder(command.out)) invalid('--out', `${frameCount} frames need a frame number in the file name: put #### where it goes (e.g. shot-####.png)`);
    const variantCount = command.variants === 'all' ? Infinity : (command.variants?.length ?? 1);
    if (variantCount > 1 && !hasVariantPlaceholder(command.out)) invalid('--out', 'several variants need {variant} in the file name (e.g. shoe-{variant}.png)');
    const cameraCount = command.cameras === 'all' ? Infinity : (command.cameras?.length ?? 1);
    if (cameraCount > 1 && !hasCameraPlaceholder(command.out)) invalid('--out', 'several cameras need {camera} in the file name (e.g. room-{camera}.png)');
  }
  return command;
}

/** Parses the whole argument list after the executable (`['render', ...]`). */
export function parseCliArgs(argv: readonly string[]): CliCommand {
  const [sub, ...rest] = argv;
  if (sub === undefined || sub === '-h' || sub === '--help' || sub === 'help') return { kind: 'help', text: usage };
  if (sub === 'farm') return parseFarmArgs(rest);
  if (sub !== 'render') invalid('command', `unknown command ${JSON.stringify(sub)} (expected "render" or "farm")`);
  return parseRenderArgs(rest);
}
