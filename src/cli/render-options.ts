/**
 * The options of `gpu-renderer render`, one row each: the parser (render-args.ts) and the help
 * text are made from this table, and docs/cli.md lists the same options (test/cli/cli-docs.test.ts).
 */
import { parseAovList, parseDuration } from '../film/option-parsing.ts';
import { parseOrigin } from '../io/resource-policy.ts';
import { parseFrameList } from '../sequence/frame-list.ts';
import type { RenderCommand } from './commands.ts';
import { helpOption, optionSetters, type CliOption } from './option-table.ts';
import { allOrNames, boundedNumber, fieldOfView, finiteNumber, integer, nonEmpty, oneOf, orbit, positiveNumber, vector3 } from './option-values.ts';

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

const { set, assign } = optionSetters<RenderCommand>();
const denoiser = oneOf('oidn', 'atrous');

export interface OptionSection<C> {
  title: string;
  options: readonly CliOption<C>[];
}

export const renderOptionSections: readonly OptionSection<RenderCommand>[] = [
  {
    title: 'Options:',
    options: [
      { flag: '--width', value: '<px>', help: `image width (default ${renderDefaults.width})`, apply: set('width', integer(1, 16384)) },
      { flag: '--height', value: '<px>', help: `image height (default ${renderDefaults.height})`, apply: set('height', integer(1, 16384)) },
      { flag: '--spp', value: '<n>', help: `samples per pixel; the ceiling with --time or --noise (default ${renderDefaults.spp})`, apply: set('spp', integer(1, 1 << 20)) },
      { flag: '--time', value: '<duration>', help: 'stop after this long, e.g. 30s, 2m, 1m30s, 250ms, or seconds (the progress bar counts down)', apply: set('timeLimitMs', parseDuration) },
      { flag: '--noise', value: '<threshold>', help: "adaptive sampling: pixels stop once their noise estimate is below this (Cycles' noise threshold, e.g. 0.01); the render ends when all have", apply: set('noiseThreshold', positiveNumber) },
      { flag: '--min-spp', value: '<n>', help: "with --noise: samples every pixel takes first (default: Cycles' rule max(4, ceil(16 / threshold^0.3)), at most spp / 4)", apply: set('minSpp', integer(2, 65536)) },
      { flag: '--spp-per-frame', value: '<n>', help: `samples per pixel per GPU frame (default ${renderDefaults.sppPerFrame})`, apply: set('sppPerFrame', integer(1, 1024)) },
      { flag: '--max-depth', value: '<n>', help: `scattering events per path, 1..32 (default ${renderDefaults.maxDepth})`, apply: set('maxDepth', integer(1, 32)) },
      { flag: '--seed', value: '<n>', help: `sampler seed, 0..4294967295 (default ${renderDefaults.seed}); the same seed gives the same image`, apply: set('seed', integer(0, 0xffffffff)) },
      { flag: '--tone-mapping', value: '<mode>', help: `neutral | aces | agx | linear (default ${renderDefaults.toneMapping})`, apply: set('toneMapping', oneOf('neutral', 'aces', 'agx', 'linear')) },
      { flag: '--exposure', value: '<x>', help: `radiance multiplier before tone mapping (default ${renderDefaults.exposure})`, apply: set('exposure', positiveNumber) },
      { flag: '--exposure-ev', value: '<stops>', help: `exposure in stops, multiplying --exposure by 2^stops (default ${renderDefaults.exposureEv})`, apply: set('exposureEv', boundedNumber(64, 'a number of stops')) },
      { flag: '--out', value: '<file>', help: `output image: .png (display-referred: exposed, tone mapped, sRGB), .exr or .hdr (scene-referred linear radiance; exposure and tone mapping do not apply) (default ${renderDefaults.out})`, apply: set('out', nonEmpty('a file name')) },
      { flag: '--aov', value: '<list>', help: '.exr only: AOV layers, comma separated: albedo, normal, depth, emission, objectId, materialId, variance, sampleCount', apply: set('aovs', parseAovList) },
      {
        flag: '--denoise', value: '[oidn|atrous]', optional: ['oidn', 'atrous'],
        help: "denoise on the GPU: oidn (Open Image Denoise's network, the default) or atrous (the fast edge-avoiding a-trous preview); an .exr keeps the raw beauty as layer raw.R/G/B",
        apply: (command, value, flag) => void (command.denoise = value === undefined ? true : denoiser(value, flag)),
      },
      { flag: '--half', help: '.exr only: half-float channels (ids and counts stay float)', apply: assign('half', true) },
      { flag: '--no-energy-compensation', help: 'render rough microfacets single-scattering only (the glTF Appendix B model as specified), without the multiple-scattering energy compensation', apply: assign('energyCompensation', false) },
      { flag: '--env', value: '<file>', help: "environment map lighting the scene: Radiance .hdr or OpenEXR, equirectangular, top row = +Y (replaces the scene's environment); also a module whose default export is a data: URL (the .exr.js HDRIs of @pmndrs/assets). --env none: no environment at all (a file named none: ./none); without --env a scene with no light is lit by the built-in neutral environment", apply: set('env', nonEmpty('a file name')) },
      { flag: '--env-intensity', value: '<x>', help: "multiplies the environment map's radiance (default 1)", apply: set('envIntensity', finiteNumber(0)) },
      { flag: '--env-rotation', value: '<deg>', help: 'rotates the environment map about +Y (default 0)', apply: set('envRotationDegrees', finiteNumber()) },
      { flag: '--negative-texels', value: '<mode>', help: `environment map texels below zero (the ringing of lossy EXR compression, e.g. the HDRIs of @pmndrs/assets): zero (set them to 0 and report how many and how much energy that adds) | error (refuse the map) (default ${renderDefaults.negativeTexels})`, apply: set('negativeTexels', oneOf('zero', 'error')) },
      { flag: '--camera', value: '<name>', help: "glTF: render from the camera (node or camera) of that name (default the scene's first camera, else a raised three-quarter view framing the scene bounds: azimuth 30, elevation 25, fov 45)", apply: set('camera', nonEmpty('a name')) },
      { flag: '--orbit', value: '<az,el[,dist]>', help: "camera on an orbit of the scene bounds' centre: azimuth in degrees about +Y from +Z towards +X, elevation in degrees (-90..90) and distance (default: the nearest at which the bounds fit the image)", apply: set('orbit', orbit) },
      { flag: '--camera-position', value: '<x,y,z>', help: "camera eye position (replaces the scene's camera)", apply: set('cameraPosition', vector3) },
      { flag: '--camera-target', value: '<x,y,z>', help: 'with --camera-position: the point looked at (default the centre of the scene bounds)', apply: set('cameraTarget', vector3) },
      { flag: '--fov', value: '<deg>', help: 'vertical field of view of the camera rendered from, in (0, 179]', apply: set('fovYDegrees', fieldOfView) },
      { flag: '--variant', value: '<name>', help: 'glTF: KHR_materials_variants variant to render', apply: set('variant', nonEmpty('a name')) },
      { flag: '--animation', value: '<name|index>', help: 'glTF: the animation to pose, by name or index (default the first)', apply: set('animation', nonEmpty('an animation name or index')) },
      { flag: '--at', value: '<seconds>', help: 'glTF: pose the animation at this time (default 0)', apply: set('at', finiteNumber(0)) },
      { flag: '--bvh-build', value: '<where>', help: 'cpu-upload (binned SAH on the CPU, the default) | gpu (LBVH built on the GPU: faster to build on a real GPU, its tree ~25-30 % costlier (SAH))', apply: set('accelerationBuildMode', oneOf('cpu-upload', 'gpu')) },
      { flag: '--instancing', value: '<mode>', help: 'auto (meshes placed many times are stored once, each placement one record of the top-level tree; the default) | always (every placement through a bottom-level tree) | off (every placement flattened into world-space triangles); the same image', apply: set('instancing', oneOf('auto', 'off', 'always')) },
      { flag: '--integrator', value: '<form>', help: 'wavefront (queued stages per bounce, the default) | megakernel (one kernel runs each path through all its bounces; the same image)', apply: set('integrator', oneOf('wavefront', 'megakernel')) },
      {
        flag: '--allow-origin', value: '<origin>',
        help: "let the scene's references fetch from this origin (e.g. https://cdn.example.com; repeatable or comma separated). By default a scene reads only files in its own folder and makes no network request",
        apply: (command, value = '', flag) => void (command.allowedOrigins ??= []).push(...value.split(',').map((origin) => parseOrigin(origin.trim(), flag))),
      },
      helpOption,
    ],
  },
  {
    title: 'Sequences (glTF; --out holds #### for the frame number, {variant} and {camera} for names):',
    options: [
      { flag: '--frames', value: '<list>', help: 'frames to render, e.g. 0-23, 0-239:10, 1,5,9 (each listed once); frame f poses the animation at f / fps', apply: set('frames', parseFrameList) },
      { flag: '--fps', value: '<n>', help: 'frames per second of --frames (default 24)', apply: set('fps', positiveNumber) },
      { flag: '--turntable', value: '<n>', help: 'orbit the framed model in n frames (with --frames: frame f looks from 360 f / n degrees)', apply: set('turntable', integer(1, 100000)) },
      { flag: '--variants', value: '<all|a,b>', help: 'one image per KHR_materials_variants variant ({variant} in --out)', apply: set('variants', allOrNames) },
      { flag: '--cameras', value: '<all|a,b>', help: 'one image per glTF camera, by name ({camera} in --out)', apply: set('cameras', allOrNames) },
      { flag: '--overwrite', help: 'render frames whose file exists (default: skip them, so an interrupted sequence resumes)', apply: assign('overwrite', true) },
    ],
  },
];

/** Every option of `render`, in the order of the help. */
export const renderOptions: readonly CliOption<RenderCommand>[] = renderOptionSections.flatMap((section) => section.options);
