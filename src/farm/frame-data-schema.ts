/**
 * The schema of a frame job's data (`FarmFrameData`). Whatever is in Redis may have been written by
 * anyone who can reach the queue, so a worker reads it as untrusted input: every key known, every
 * string and array bounded, every number finite and in the range the command line would accept,
 * and nothing that widens what the worker may touch. Network origins in particular are a worker's
 * own setting (`farm worker --allow-origin`): a job naming them is refused. A fault is a
 * FARM_JOB_REFUSED error whose `field` is the job's key path (`render.width`, `item.turntableCamera.up[1]`).
 */
import { wavefrontAovNames } from '../film/aovs.ts';
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import type { FarmFrameData } from './farm-job.ts';

/** Limits of a frame job's data. */
export const frameDataLimits = Object.freeze({
  /** The whole job's data as JSON, in characters. */
  jsonChars: 64 * 1024,
  /** A path (scene, environment map, output). */
  pathChars: 4096,
  /** A name (camera, variant, animation). */
  nameChars: 256,
  /** A job's name (an asset's file name and a hash, by default). */
  jobChars: 300,
  /** Coordinates, as the scene checks bound them (beyond this, float32 products overflow). */
  coordinate: 1e18,
});

const JOB_NAME = /^[A-Za-z0-9._-]+$/;

type Check = (value: unknown, field: string) => void;

function refuse(field: string, message: string): never {
  throw new GpuRendererError('FARM_JOB_REFUSED', message, { field });
}

function shown(value: unknown): string {
  if (typeof value === 'string') return JSON.stringify(value.length > 60 ? `${value.slice(0, 60)}...` : value);
  if (typeof value === 'number') return String(value);
  return Array.isArray(value) ? 'an array' : value === null ? 'null' : typeof value;
}

const text = (max: number, pattern?: RegExp): Check => (value, field) => {
  if (typeof value !== 'string' || value === '') refuse(field, `expected a non-empty string, got ${shown(value)}`);
  if (value.length > max) refuse(field, `longer than ${max} characters (${value.length})`);
  if ([...value].some((ch) => ch.charCodeAt(0) < 0x20)) refuse(field, 'contains control characters');
  if (pattern !== undefined && !pattern.test(value)) refuse(field, `does not match ${pattern}, got ${shown(value)}`);
};

/** An absolute path (the submitting machine's; the worker maps and confines it later). */
const path: Check = (value, field) => {
  text(frameDataLimits.pathChars)(value, field);
  const p = value as string;
  if (!p.startsWith('/') && !/^[A-Za-z]:[\\/]/.test(p) && !p.startsWith('\\\\')) refuse(field, `expected an absolute path, got ${shown(p)}`);
};

const name = text(frameDataLimits.nameChars);

const integer = (min: number, max: number): Check => (value, field) => {
  if (typeof value !== 'number' || !Number.isInteger(value) || value < min || value > max) refuse(field, `expected an integer in ${min}..${max}, got ${shown(value)}`);
};

/** A finite number in [min, max] (`exclusiveMin`: above min). */
const number = (min: number, max: number, exclusiveMin = false): Check => (value, field) => {
  if (typeof value !== 'number' || !Number.isFinite(value)) refuse(field, `expected a finite number, got ${shown(value)}`);
  if (value > max || value < min || (exclusiveMin && value === min)) refuse(field, `expected a number in ${exclusiveMin ? '(' : '['}${min}, ${max}], got ${value}`);
};

const oneOf = (...words: readonly (string | boolean)[]): Check => (value, field) => {
  if (!words.includes(value as string | boolean)) refuse(field, `expected one of ${words.map((w) => JSON.stringify(w)).join(', ')}, got ${shown(value)}`);
};

const boolean = oneOf(true, false);

const array = (of: Check, min: number, max: number): Check => (value, field) => {
  if (!Array.isArray(value)) refuse(field, `expected an array, got ${shown(value)}`);
  if (value.length < min || value.length > max) refuse(field, `expected ${min === max ? min : `${min} to ${max}`} items, got ${value.length}`);
  value.forEach((item, i) => of(item, `${field}[${i}]`));
};

const coordinate = number(-frameDataLimits.coordinate, frameDataLimits.coordinate);
const vector3 = array(coordinate, 3, 3);

interface Shape {
  [key: string]: { check: Check; required?: boolean } | { refused: string };
}

const required = (check: Check) => ({ check, required: true });
const optional = (check: Check) => ({ check });

/** A plain object with exactly the shape's keys (undefined counts as absent: JSON drops it). */
const object = (shape: Shape): Check => (value, field) => {
  const at = (key: string): string => (field === '' ? key : `${field}.${key}`);
  if (typeof value !== 'object' || value === null || Array.isArray(value)) refuse(field || '/', `expected an object, got ${shown(value)}`);
  const proto = Object.getPrototypeOf(value);
  if (proto !== Object.prototype && proto !== null) refuse(field || '/', 'expected a plain object');
  const o = value as Record<string, unknown>;
  for (const key of Object.keys(o)) {
    // Own keys only: `__proto__` and the like name no rule.
    const rule = Object.hasOwn(shape, key) ? shape[key] : undefined;
    if (rule === undefined) refuse(at(key), `unknown key (a frame job has ${Object.keys(shape).filter((k) => !('refused' in shape[k]!)).join(', ')})`);
    if ('refused' in rule) {
      if (o[key] !== undefined) refuse(at(key), rule.refused);
      continue;
    }
    if (o[key] !== undefined) rule.check(o[key], at(key));
  }
  for (const [key, rule] of Object.entries(shape)) if ('required' in rule && rule.required && o[key] === undefined) refuse(at(key), 'missing');
};

const camera = object({
  type: optional(oneOf('perspective', 'orthographic')),
  position: required(vector3),
  target: required(vector3),
  up: optional(vector3),
  fovYDegrees: optional(number(0, 179, true)),
  orthographicHeight: optional(number(0, frameDataLimits.coordinate, true)),
});

const sequenceKey = 'a frame job renders one planned frame; its sequence is planned at submission';

/** The render settings: the `render` command's options, as the command line bounds them. */
const render = object({
  kind: required(oneOf('render')),
  scenePath: required(path),
  camera: optional(name),
  variant: optional(name),
  width: required(integer(1, 16384)),
  height: required(integer(1, 16384)),
  spp: required(integer(1, 1 << 20)),
  sppPerFrame: required(integer(1, 1024)),
  maxDepth: required(integer(1, 32)),
  seed: required(integer(0, 0xffffffff)),
  toneMapping: required(oneOf('neutral', 'aces', 'agx', 'linear')),
  exposure: required(number(0, 1e30, true)),
  exposureEv: required(number(-64, 64)),
  out: required(path),
  format: required(oneOf('png', 'exr', 'hdr')),
  timeLimitMs: optional(number(0, 31_536_000_000, true)),
  noiseThreshold: optional(number(0, 1e30, true)),
  minSpp: optional(integer(2, 65536)),
  aovs: required(array(oneOf(...wavefrontAovNames), 0, wavefrontAovNames.length)),
  denoise: required(oneOf(true, false, 'oidn', 'atrous')),
  half: required(boolean),
  energyCompensation: required(boolean),
  env: optional((value, field) => (value === 'none' ? undefined : path(value, field))),
  envIntensity: optional(number(0, 1e30)),
  envRotationDegrees: optional(number(-1e6, 1e6)),
  animation: optional(name),
  at: optional(number(0, 1e9)),
  fps: optional(number(0, 1e6, true)),
  overwrite: optional(boolean),
  negativeTexels: required(oneOf('zero', 'error')),
  cameraPosition: optional(vector3),
  cameraTarget: optional(vector3),
  orbit: optional(object({ azimuthDegrees: required(number(-1e6, 1e6)), elevationDegrees: required(number(-90, 90)), distance: optional(number(0, frameDataLimits.coordinate, true)) })),
  fovYDegrees: optional(number(0, 179, true)),
  accelerationBuildMode: optional(oneOf('cpu-upload', 'gpu')),
  integrator: optional(oneOf('wavefront', 'megakernel')),
  allowedOrigins: { refused: "network origins are the worker's own setting (farm worker --allow-origin, GPU_RENDERER_FARM_ALLOW_ORIGINS), never a job's" },
  frames: { refused: sequenceKey },
  turntable: { refused: sequenceKey },
  variants: { refused: sequenceKey },
  cameras: { refused: sequenceKey },
});

const frameData = object({
  job: required(text(frameDataLimits.jobChars, JOB_NAME)),
  index: required(integer(0, 1_000_000)),
  path: required(path),
  item: required(object({
    index: required(integer(0, 1_000_000)),
    frame: required(integer(0, 1e9)),
    time: required(number(-1e9, 1e9)),
    variant: optional(name),
    cameraIndex: optional(integer(0, 65535)),
    cameraName: optional(name),
    turntableCamera: optional(camera),
  })),
  render: required(render),
});

/**
 * Checks a frame job's data against the schema and returns it typed; FARM_JOB_REFUSED naming the
 * field otherwise. The size of the whole is checked first, so nothing larger is walked.
 */
export function validateFrameData(data: unknown): FarmFrameData {
  let json: string | undefined;
  try {
    json = JSON.stringify(data);
  } catch {
    refuse('/', 'not JSON data');
  }
  if (json === undefined) refuse('/', 'no job data');
  if (json.length > frameDataLimits.jsonChars) refuse('/', `the job's data is ${json.length} characters of JSON, over the limit of ${frameDataLimits.jsonChars}`);
  frameData(data, '');
  return data as FarmFrameData;
}

/** The frame's job name and index when they at least are valid (to record a refusal against its job), else undefined. */
export function frameJobOf(data: unknown): { job: string; index: number } | undefined {
  if (typeof data !== 'object' || data === null) return undefined;
  const { job, index } = data as { job?: unknown; index?: unknown };
  if (typeof job !== 'string' || job.length > frameDataLimits.jobChars || !JOB_NAME.test(job)) return undefined;
  if (typeof index !== 'number' || !Number.isInteger(index) || index < 0 || index > 1_000_000) return undefined;
  return { job, index };
}
