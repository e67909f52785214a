import { fail, requireInteger, requireNumberInRange, requireVec } from '../errors/validate.ts';
import { validateLightingOptions, type LightingConfig } from '../lighting/lighting-options.ts';
import { maxRadiance } from '../scene/limits.ts';
import type { WavefrontToneMapping } from '../scene/types.ts';
import { normalizeWavefrontCamera, type WavefrontCamera } from './camera.ts';
import { outputOptionNames, parseOutputOptions, type WavefrontOutputConfig } from './output-options.ts';
import type { PathTracingIntegrator, WavefrontPathTracingOptions } from './types.ts';
import type { AccelerationBuildMode } from './scene/prepare-scene.ts';
import { instancingModes, type InstancingMode } from './scene/instancing.ts';

export const maxWavefrontDepth = 32;
export const maxWavefrontImageSize = 16384;
/** Frames renderFrame keeps in flight by default (statistics come back through a ring this deep). */
export const defaultFramesInFlight = 2;
export const maxFramesInFlight = 4;

/** Validated renderer settings (everything but the scene geometry). */
export interface WavefrontPathTracingComputeConfig {
  width: number;
  height: number;
  maxDepth: number;
  samplesPerPixel: number;
  /** Explicit bound on paths per wave (tileSize^2); null: sized to the device and the work. */
  tileSize: number | null;
  /** How a wave's paths run: queued stages per bounce, or one kernel per path (megakernel). */
  integrator: PathTracingIntegrator;
  /** Frames whose submission may run ahead of their statistics (renderFrame). */
  framesInFlight: number;
  seed: number;
  camera: WavefrontCamera;
  /** Uniform environment radiance; black when omitted. */
  environment: [number, number, number];
  toneMapping: WavefrontToneMapping;
  exposure: number;
  /** Accumulate albedo, normal, depth, id and variance AOVs of the first non-specular hit. */
  aovs: boolean;
  /** Adaptive sampling, denoiser, presentation, submission bounds and feature flags (output-options.ts). */
  output: WavefrontOutputConfig;
  /** Environment map or sky, punctual and area lights, portals, light sampler (src/lighting/lighting-options.ts). */
  lighting: LightingConfig;
  /** Multiple-scattering energy compensation of rough microfacet lobes (materials). */
  energyCompensation: boolean;
  /** Where the BVH is built: 'cpu-upload' (binned SAH on the CPU, uploaded) or 'gpu' (LBVH in WGSL). */
  accelerationBuildMode: AccelerationBuildMode;
  /** Which mesh placements are traced through shared bottom-level trees (scene/instancing.ts). */
  instancing: InstancingMode;
}

const toneMappings: readonly WavefrontToneMapping[] = ['neutral', 'aces', 'linear', 'agx'];
/** Every integrator form, the default first. */
export const pathTracingIntegrators: readonly PathTracingIntegrator[] = ['wavefront', 'megakernel'];

/** Every option name the renderer understands; any other key is a typed error, never ignored. */
export const wavefrontOptionNames: ReadonlySet<string> = new Set<keyof WavefrontPathTracingOptions>([
  'width', 'height', 'maxDepth', 'samplesPerPixel', 'tileSize', 'integrator', 'framesInFlight', 'seed', 'camera', 'meshes', 'instances', 'materials', 'textures',
  'images', 'sceneObjects', 'lights', 'environment', 'toneMapping', 'exposure', 'aovs', 'shaderSpecialization', 'canvas', 'device', 'powerPreference',
  ...outputOptionNames,
  // Lighting (src/lighting/lighting-options.ts).
  'environmentMap', 'environmentLighting', 'environmentPortals', 'environmentPortalMode', 'lightSampler', 'environmentSampling',
  'energyCompensation',
  'accelerationBuildMode',
  'instancing',
]);

/** Validates the non-geometry options; every error names its field. */
export function createWavefrontPathTracingComputeConfig(options: Partial<WavefrontPathTracingOptions>): WavefrontPathTracingComputeConfig {
  if (typeof options !== 'object' || options === null) fail('INVALID_OPTION', 'options', 'expected an options object');
  for (const key of Object.keys(options)) {
    if (!wavefrontOptionNames.has(key)) fail('INVALID_OPTION', key, `unknown option (expected one of ${[...wavefrontOptionNames].join(', ')})`);
  }
  const width = requireInteger(options.width, 'width', { min: 1, max: maxWavefrontImageSize });
  const height = requireInteger(options.height, 'height', { min: 1, max: maxWavefrontImageSize });
  const maxDepth = options.maxDepth === undefined ? 8 : requireInteger(options.maxDepth, 'maxDepth', { min: 1, max: maxWavefrontDepth });
  const samplesPerPixel = options.samplesPerPixel === undefined ? 1 : requireInteger(options.samplesPerPixel, 'samplesPerPixel', { min: 1, max: 65536 });
  const tileSize = options.tileSize === undefined ? null : requireInteger(options.tileSize, 'tileSize', { min: 8, max: 1024 });
  const integrator = options.integrator ?? 'wavefront';
  if (!pathTracingIntegrators.includes(integrator)) fail('INVALID_OPTION', 'integrator', `expected one of ${pathTracingIntegrators.map((i) => JSON.stringify(i)).join(', ')}, got ${JSON.stringify(integrator)}`);
  const framesInFlight = options.framesInFlight === undefined ? defaultFramesInFlight : requireInteger(options.framesInFlight, 'framesInFlight', { min: 1, max: maxFramesInFlight });
  const seed = options.seed === undefined ? 0 : requireInteger(options.seed, 'seed', { min: 0, max: 0xffffffff });
  const camera = normalizeWavefrontCamera(options.camera);
  let environment: [number, number, number] = [0, 0, 0];
  if (options.environment !== undefined) {
    if (typeof options.environment !== 'object' || options.environment === null) fail('INVALID_OPTION', 'environment', 'expected { color: [r, g, b] }');
    for (const key of Object.keys(options.environment)) if (key !== 'color') fail('INVALID_OPTION', `environment.${key}`, 'unknown environment key');
    const c = requireVec(options.environment.color, 3, 'environment.color');
    c.forEach((v, i) => requireNumberInRange(v, `environment.color[${i}]`, { min: 0, max: maxRadiance }));
    environment = [c[0]!, c[1]!, c[2]!];
  }
  const lighting = validateLightingOptions(options, environment);
  const toneMapping = options.toneMapping ?? 'neutral';
  if (!toneMappings.includes(toneMapping)) fail('INVALID_OPTION', 'toneMapping', `expected one of ${toneMappings.join(', ')}`);
  const exposure = options.exposure === undefined ? 1 : requireNumberInRange(options.exposure, 'exposure', { min: 0 });
  if (options.aovs !== undefined && typeof options.aovs !== 'boolean') fail('INVALID_OPTION', 'aovs', 'expected a boolean');
  if (options.energyCompensation !== undefined && typeof options.energyCompensation !== 'boolean') fail('INVALID_OPTION', 'energyCompensation', 'expected a boolean');
  const accelerationBuildMode = options.accelerationBuildMode ?? 'cpu-upload';
  if (accelerationBuildMode !== 'cpu-upload' && accelerationBuildMode !== 'gpu') fail('INVALID_OPTION', 'accelerationBuildMode', `expected "cpu-upload" or "gpu", got ${JSON.stringify(accelerationBuildMode)}`);
  const instancing = options.instancing ?? 'auto';
  if (!instancingModes.includes(instancing)) fail('INVALID_OPTION', 'instancing', `expected one of ${instancingModes.map((m) => JSON.stringify(m)).join(', ')}, got ${JSON.stringify(instancing)}`);
  const output = parseOutputOptions(options);
  return {
    width, height, maxDepth, samplesPerPixel, tileSize, integrator, framesInFlight, seed, camera, environment, toneMapping, exposure, aovs: options.aovs ?? false, output, lighting,
    energyCompensation: options.energyCompensation ?? true,
    accelerationBuildMode,
    instancing,
  };
}
