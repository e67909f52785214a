/**
 * A farm job: a render command over a glTF asset whose sequence (frames, turntable, variants,
 * cameras) is split into one queue job per frame. It comes from the `render` options on the command
 * line, or from a JSON job file whose keys are those options in camelCase:
 *
 *   { "scene": "assets/fox.glb", "out": "frames/fox-####.png", "frames": "0-23", "fps": 24,
 *     "animation": "Walk", "width": 640, "height": 360, "spp": 64, "env": "studio.hdr" }
 *
 * (`frames` also as an array of numbers; `variants` and `cameras` as "all" or arrays of names;
 * boolean flags as true; relative paths resolve against the job file's directory). Job files are
 * validated by the same parser as the command line; their errors name the key as a JSON pointer
 * (`/frames`).
 */
import { isAbsolute, resolve } from 'node:path';
import { isSequence, parseRenderArgs, type RenderCommand } from '../cli/args.ts';
import { ENV_NONE } from '../cli/environment-flags.ts';
import { GpuRendererError, isGpuRendererError } from '../errors/gpu-renderer-error.ts';
import type { GltfSequenceItem } from '../sequence/gltf-sequence.ts';

/** What one queue job renders: a frame of a farm job. */
export interface FarmFrameData {
  /** The farm job's name. */
  job: string;
  /** The frame's position in the job's sequence. */
  index: number;
  /** Absolute output path. */
  path: string;
  item: GltfSequenceItem;
  /** The render settings (absolute paths; the sequence options are already planned into `item`). */
  render: RenderCommand;
}

function invalid(field: string, message: string): never {
  throw new GpuRendererError('INVALID_OPTION', message, { field });
}

const pathKeys = new Set(['scene', 'out', 'env']);

function flagOf(key: string): string {
  return `--${key.replace(/[A-Z]/g, (c) => `-${c.toLowerCase()}`)}`;
}

/** `--env-intensity` -> `envIntensity`: a job file's key for a command-line flag. */
export function jobKeyOf(flag: string): string {
  return flag.replace(/^--/, '').replace(/-([a-z])/g, (_, c: string) => c.toUpperCase());
}

/**
 * A job file's object as `render` arguments, parsed by the command line's parser; errors are
 * re-labelled with the job file's key as a JSON pointer.
 */
export function parseJobFile(text: string, file: string, baseDir: string): RenderCommand {
  let json: unknown;
  try {
    json = JSON.parse(text);
  } catch (error) {
    invalid('', `${file} is not JSON: ${(error as Error).message}`);
  }
  if (typeof json !== 'object' || json === null || Array.isArray(json)) invalid('', `${file}: expected a JSON object of render options`);
  const argv: string[] = [];
  let scene: string | undefined;
  for (const [key, value] of Object.entries(json as Record<string, unknown>)) {
    const at = `/${key}`;
    if (key === 'scene') {
      if (typeof value !== 'string' || value === '') invalid(at, 'expected the asset path');
      scene = isAbsolute(value) ? value : resolve(baseDir, value);
      continue;
    }
    if (key === 'energyCompensation') {
      if (typeof value !== 'boolean') invalid(at, 'expected true or false');
      if (!value) argv.push('--no-energy-compensation');
      continue;
    }
    const flag = flagOf(key);
    if (typeof value === 'boolean') {
      if (value) argv.push(flag);
      continue;
    }
    let text: string;
    if (typeof value === 'number') text = String(value);
    else if (typeof value === 'string') text = pathKeys.has(key) && value !== '' && !isAbsolute(value) ? resolve(baseDir, value) : value;
    else if (Array.isArray(value) && value.every((v) => typeof v === 'string' || typeof v === 'number')) text = value.join(',');
    else invalid(at, `expected a string, a number, true or an array, got ${JSON.stringify(value)}`);
    argv.push(`${flag}=${text}`);
  }
  if (scene === undefined) invalid('/scene', `${file}: the job names no asset ("scene")`);
  try {
    const command = parseRenderArgs([scene, ...argv]);
    if (command.kind !== 'render') invalid('', 'a job file cannot ask for help');
    return command;
  } catch (error) {
    if (!isGpuRendererError(error) || error.field === undefined || !error.field.startsWith('--')) throw error;
    const pointer = error.field === '--out' || error.field === '--scene' ? `/${error.field.slice(2)}` : `/${jobKeyOf(error.field)}`;
    throw new GpuRendererError(error.code, `${file}: ${error.message.slice(error.field.length + 2)}`, { field: pointer, cause: error });
  }
}

/** Checks a command can be a farm job and makes its paths absolute (workers may run elsewhere, with the same shared mounts). */
export function farmRenderCommand(command: RenderCommand, cwd = process.cwd()): RenderCommand {
  if (command.scenePath === undefined) invalid('scene', 'a farm job renders a glTF asset; name it');
  if (!isSequence(command)) invalid('--frames', 'a farm job is a sequence: give --frames, --turntable, --variants or --cameras');
  // Origins are the worker's to allow (farm worker --allow-origin): a job carrying them would be refused.
  if (command.allowedOrigins !== undefined && command.allowedOrigins.length > 0) {
    invalid('--allow-origin', "a farm job cannot allow network origins: workers fetch only from their own (farm worker --allow-origin or GPU_RENDERER_FARM_ALLOW_ORIGINS)");
  }
  const { allowedOrigins: _origins, ...rest } = command;
  return {
    ...rest,
    scenePath: resolve(cwd, command.scenePath),
    out: resolve(cwd, command.out),
    ...(command.env !== undefined ? { env: command.env === ENV_NONE ? ENV_NONE : resolve(cwd, command.env) } : {}),
  };
}

/** The render settings a frame job carries: the command without its sequence options. */
export function frameRenderSettings(command: RenderCommand): RenderCommand {
  const { frames: _frames, turntable: _turntable, variants: _variants, cameras: _cameras, ...rest } = command;
  return rest;
}
