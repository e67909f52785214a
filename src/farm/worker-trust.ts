/**
 * What a farm worker trusts: its own configuration, never a job's. A worker is given the folders it
 * may read assets from (`assetRoots`) and write frames into (`outputRoots`), a path map for storage
 * mounted elsewhere than on the submitting machine (Deadline's path mapping, Flamenco's two-way
 * variables: the longest matching FROM prefix is replaced by its TO), and the network origins an
 * asset's references may be fetched from. A job's scene and environment map must resolve, after
 * the path map and after symbolic links (realpath), inside an asset root; its output file's nearest
 * existing folder, likewise, inside an output root. The asset's own references are bounded by the
 * same asset root through the resource policy's `root` (io/resource-policy.ts), which checks every
 * reference's real path when it is read.
 */
import { mkdir, realpath } from 'node:fs/promises';
import { basename, delimiter, dirname, resolve } from 'node:path';
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { parseOrigin, type ResourcePolicy } from '../io/resource-policy.ts';
import type { FarmFrameData } from './farm-job.ts';
import { checkPathMapping, isUnder, mapJobPath, parsePathMapping, type FarmPathMapping } from './path-map.ts';

export { mapJobPath, parsePathMapping, type FarmPathMapping } from './path-map.ts';

/** The trust options of `runFarmWorker`. */
export interface FarmTrustOptions {
  /** Folders frames may be written into (default GPU_RENDERER_FARM_OUTPUT_ROOTS). At least one is required. */
  outputRoots?: readonly string[];
  /** Folders assets and environment maps, and everything they reference, may be read from (default GPU_RENDERER_FARM_ASSET_ROOTS). At least one is required. */
  assetRoots?: readonly string[];
  /** Applied to a job's paths before they are confined (default GPU_RENDERER_FARM_PATH_MAP). */
  pathMap?: readonly FarmPathMapping[];
  /** Origins an asset's references may be fetched from (default GPU_RENDERER_FARM_ALLOW_ORIGINS, else none). */
  allowedOrigins?: readonly string[];
}

/** A worker's trust, resolved: roots as real paths. */
export interface FarmTrust {
  outputRoots: readonly string[];
  assetRoots: readonly string[];
  pathMap: readonly FarmPathMapping[];
  allowedOrigins: readonly string[];
}

/** The environment variables a worker reads its trust from when the options leave it out. */
export const farmTrustEnv = Object.freeze({
  outputRoots: 'GPU_RENDERER_FARM_OUTPUT_ROOTS',
  assetRoots: 'GPU_RENDERER_FARM_ASSET_ROOTS',
  pathMap: 'GPU_RENDERER_FARM_PATH_MAP',
  allowedOrigins: 'GPU_RENDERER_FARM_ALLOW_ORIGINS',
});

function invalid(field: string, message: string): never {
  throw new GpuRendererError('INVALID_OPTION', message, { field });
}

function refused(field: string, message: string): never {
  throw new GpuRendererError('FARM_JOB_REFUSED', message, { field });
}

const list = (value: string | undefined, separator: string | RegExp): string[] => (value ?? '').split(separator).map((s) => s.trim()).filter((s) => s !== '');

async function realRoot(root: string, field: string): Promise<string> {
  if (typeof root !== 'string' || root === '') invalid(field, `expected a folder, got ${JSON.stringify(root)}`);
  try {
    return await realpath(resolve(root));
  } catch (error) {
    invalid(field, `cannot use ${JSON.stringify(root)} as a root: ${(error as Error).message}`);
  }
}

/**
 * The worker's trust from its options, else its environment. No output root or no asset root is
 * an INVALID_OPTION error naming `--output-root` / `--asset-root`: a worker without them would
 * read and write wherever a job said, so it does not start.
 */
export async function resolveFarmTrust(options: FarmTrustOptions = {}, env: Record<string, string | undefined> = process.env): Promise<FarmTrust> {
  const roots = async (given: readonly string[] | undefined, variable: string, flag: string, what: string): Promise<string[]> => {
    const named = given !== undefined && given.length > 0 ? [...given] : list(env[variable], delimiter);
    if (named.length === 0) invalid(flag, `a farm worker needs at least one ${what} root (${flag} DIR, repeatable, or ${variable}); it reads and writes nothing outside its roots`);
    return Promise.all(named.map((root) => realRoot(root, flag)));
  };
  const outputRoots = await roots(options.outputRoots, farmTrustEnv.outputRoots, '--output-root', 'output');
  const assetRoots = await roots(options.assetRoots, farmTrustEnv.assetRoots, '--asset-root', 'asset');
  const pathMap = options.pathMap !== undefined && options.pathMap.length > 0
    ? options.pathMap.map((m) => checkPathMapping(m, '--path-map'))
    : list(env[farmTrustEnv.pathMap], /[;\n]/).map((entry) => parsePathMapping(entry, farmTrustEnv.pathMap));
  const origins = options.allowedOrigins !== undefined && options.allowedOrigins.length > 0 ? { list: options.allowedOrigins, field: '--allow-origin' } : { list: list(env[farmTrustEnv.allowedOrigins], ','), field: farmTrustEnv.allowedOrigins };
  const allowedOrigins = origins.list.map((origin) => parseOrigin(origin, origins.field));
  return Object.freeze({ outputRoots, assetRoots, pathMap, allowedOrigins });
}

/**
 * The real path of `path` (its nearest existing ancestor's realpath, and the part that does not
 * exist yet), and the root it lies in; FARM_JOB_REFUSED naming `field` when it lies in none.
 */
async function confine(path: string, roots: readonly string[], field: string, what: string): Promise<{ real: string; root: string; exists: boolean }> {
  let existing = path;
  const missing: string[] = [];
  let real: string | undefined;
  while (real === undefined) {
    try {
      real = await realpath(existing);
    } catch (error) {
      const code = (error as { code?: string }).code;
      if (code !== 'ENOENT' && code !== 'ENOTDIR') throw error;
      const parent = dirname(existing);
      if (parent === existing) refused(field, `${JSON.stringify(path)} has no existing folder`);
      missing.unshift(basename(existing));
      existing = parent;
    }
  }
  const full = resolve(real, ...missing);
  const root = roots.find((r) => isUnder(full, r));
  if (root === undefined) refused(field, `${JSON.stringify(path)}${full !== path ? ` (really ${JSON.stringify(full)})` : ''} lies outside the worker's ${what} roots (${roots.join(', ')})`);
  return { real: full, root, exists: missing.length === 0 };
}

/** A frame job's data with its paths mapped and confined, and the resource policies its reads go through. */
export interface ConfinedFrame {
  data: FarmFrameData;
  /** The scene's policy: the worker's origins, the asset root holding the scene as the root of every read. */
  scenePolicy: ResourcePolicy;
  /** The environment map's policy (its own asset root). */
  envPolicy: ResourcePolicy;
}

/**
 * Maps a frame's paths (`render.scenePath`, `render.env`, `path`, `render.out`) and confines them
 * to the worker's roots, symbolic links followed; FARM_JOB_REFUSED naming the job's field when one
 * lies outside. Nothing is created or written here.
 */
export async function confineFrame(data: FarmFrameData, trust: FarmTrust): Promise<ConfinedFrame> {
  const render = data.render;
  const scene = await confine(mapJobPath(render.scenePath!, trust.pathMap), trust.assetRoots, 'render.scenePath', 'asset');
  let env: { real: string; root: string } | undefined;
  if (render.env !== undefined && render.env !== 'none') env = await confine(mapJobPath(render.env, trust.pathMap), trust.assetRoots, 'render.env', 'asset');
  const output = await confine(mapJobPath(data.path, trust.pathMap), trust.outputRoots, 'path', 'output');
  const out = await confine(mapJobPath(render.out, trust.pathMap), trust.outputRoots, 'render.out', 'output');
  const origins = { allowedOrigins: trust.allowedOrigins };
  return {
    data: { ...data, path: output.real, render: { ...render, scenePath: scene.real, out: out.real, ...(env !== undefined ? { env: env.real } : {}) } },
    scenePolicy: { ...origins, root: scene.root },
    envPolicy: { ...origins, root: env?.root ?? scene.root },
  };
}

/**
 * Creates the output file's folder inside its root and checks its real path again just before the
 * write (a link swapped in since `confineFrame` is refused; nothing is written through it).
 */
export async function prepareOutputFolder(path: string, trust: FarmTrust): Promise<void> {
  const folder = dirname(path);
  const confined = await confine(folder, trust.outputRoots, 'path', 'output');
  // mkdir below the real ancestor: every folder it creates lies inside the root.
  await mkdir(confined.real, { recursive: true });
  const real = await realpath(confined.real);
  if (!trust.outputRoots.some((r) => isUnder(real, r))) refused('path', `${JSON.stringify(folder)} (really ${JSON.stringify(real)}) lies outside the worker's output roots`);
}
