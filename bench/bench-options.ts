/**
 * Options of `npm run bench`, from the command line (after `--`) and the environment:
 *   --baseline <ref> | BENCH_BASELINE_REF   git ref to compare against (default: bench/baseline.json)
 *   --no-baseline    | BENCH_BASELINE=0     measure the current version only
 *   --rounds <n>     | BENCH_ROUNDS         child processes per version, alternated (default 3)
 *   --no-bvh         | BENCH_BVH=0          skip the BVH build benchmark
 *   --bvh-only       | BENCH_ONLY=bvh       run the BVH build benchmark alone
 *   --no-gltf        | BENCH_GLTF=0         skip the glTF benchmark (load + BVH, textures)
 *   --gltf-only      | BENCH_ONLY=gltf      run the glTF benchmark alone
 *   --no-raster      | BENCH_RASTER=0       skip the raster renderer benchmark
 *   --raster-only    | BENCH_ONLY=raster    run the raster renderer benchmark alone
 *   --no-lighting    | BENCH_LIGHTING=0     skip the lighting benchmark (environment sampling, light tree, portals)
 *   --lighting-only  | BENCH_ONLY=lighting  run the lighting benchmark alone
 *   --no-instancing  | BENCH_INSTANCING=0   skip the instancing benchmark (two-level acceleration: forest, flattened vs instanced)
 *   --instancing-only | BENCH_ONLY=instancing run the instancing benchmark alone
 *   --output         | BENCH_OUTPUT=1       add the production-output benchmark (off by default: minutes)
 *   --output-only    | BENCH_ONLY=output    run the production-output benchmark alone
 *   --no-gpu         | BENCH_GPU=0          skip the GPU figures (bench/gpu.ts: the path tracer's defaults at 1080p)
 *   --gpu-only       | BENCH_ONLY=gpu       run the GPU figures alone (BENCH_GPU_SCALE: fraction of their samples)
 *   --browser        | BENCH_BROWSER=1      add the browser section (ours beside three-gpu-pathtracer in Chromium; off by
 *                                            default: minutes; BENCH_BROWSER_SECONDS, _SIZE, _SCENES, _REFERENCE_SPP: bench/browser.ts)
 *   --browser-only   | BENCH_ONLY=browser   run the browser section alone
 * The command line wins over the environment. BENCH_SPP is read by the path tracer harnesses.
 */
import { parseArgs } from 'node:util';

export const DEFAULT_ROUNDS = 3;

export type BaselineChoice =
  | { enabled: true; ref: string; source: 'command line' | 'BENCH_BASELINE_REF' | 'bench/baseline.json'; description: string | null }
  | { enabled: false; reason: string };

export interface BenchOptions {
  baseline: BaselineChoice;
  /** Child processes per version; versions alternate (baseline, current, baseline, current, ...). */
  rounds: number;
  bvh: boolean;
  /** Run the glTF benchmark (bench/gltf.ts). */
  gltf: boolean;
  raster: boolean;
  /** The lighting benchmark (bench/lighting.ts). */
  lighting: boolean;
  /** The instancing benchmark (bench/instancing.ts, a child process). */
  instancing: boolean;
  /** The production-output benchmark: opt-in. */
  output: boolean;
  /** The GPU figures (bench/gpu.ts). */
  gpu: boolean;
  /** The browser section (bench/browser.ts): opt-in. */
  browser: boolean;
  /** Run the path tracer comparison (off with --bvh-only / --gltf-only). */
  pathTracer: boolean;
}

export interface BaselineFile {
  ref: string;
  description?: string;
}

const OFF = new Set(['0', 'false', 'no', 'off']);

function positiveInteger(text: string, name: string): number {
  const n = Number(text);
  if (!Number.isInteger(n) || n < 1) throw new Error(`${name}: expected a positive integer, got ${JSON.stringify(text)}`);
  return n;
}

/** Parses bench/baseline.json's text; null when it does not name a ref. */
export function parseBaselineFile(text: string): BaselineFile | null {
  const value = JSON.parse(text) as unknown;
  if (typeof value !== 'object' || value === null) return null;
  const { ref, description } = value as Record<string, unknown>;
  if (typeof ref !== 'string' || ref.trim() === '') return null;
  return { ref: ref.trim(), ...(typeof description === 'string' ? { description } : {}) };
}

export function parseBenchOptions(
  argv: readonly string[],
  env: Readonly<Record<string, string | undefined>>,
  baselineFile: BaselineFile | null,
): BenchOptions {
  const { values } = parseArgs({
    args: [...argv],
    options: {
      baseline: { type: 'string' },
      'no-baseline': { type: 'boolean' },
      rounds: { type: 'string' },
      'no-bvh': { type: 'boolean' },
      'bvh-only': { type: 'boolean' },
      'no-gltf': { type: 'boolean' },
      'gltf-only': { type: 'boolean' },
      'no-raster': { type: 'boolean' },
      'raster-only': { type: 'boolean' },
      'no-lighting': { type: 'boolean' },
      'lighting-only': { type: 'boolean' },
      'no-instancing': { type: 'boolean' },
      'instancing-only': { type: 'boolean' },
      output: { type: 'boolean' },
      'no-output': { type: 'boolean' },
      'output-only': { type: 'boolean' },
      'no-gpu': { type: 'boolean' },
      'gpu-only': { type: 'boolean' },
      browser: { type: 'boolean' },
      'no-browser': { type: 'boolean' },
      'browser-only': { type: 'boolean' },
    },
    strict: true,
    allowPositionals: false,
  });

  let baseline: BaselineChoice;
  if (values['no-baseline']) baseline = { enabled: false, reason: '--no-baseline' };
  else if (values.baseline !== undefined) baseline = { enabled: true, ref: values.baseline, source: 'command line', description: null };
  else if (env.BENCH_BASELINE !== undefined && OFF.has(env.BENCH_BASELINE.toLowerCase())) baseline = { enabled: false, reason: `BENCH_BASELINE=${env.BENCH_BASELINE}` };
  else if (env.BENCH_BASELINE_REF) baseline = { enabled: true, ref: env.BENCH_BASELINE_REF, source: 'BENCH_BASELINE_REF', description: null };
  else if (baselineFile) baseline = { enabled: true, ref: baselineFile.ref, source: 'bench/baseline.json', description: baselineFile.description ?? null };
  else baseline = { enabled: false, reason: 'bench/baseline.json names no ref' };

  const roundsText = values.rounds ?? env.BENCH_ROUNDS;
  const rounds = roundsText === undefined || roundsText === '' ? DEFAULT_ROUNDS : positiveInteger(roundsText, values.rounds !== undefined ? '--rounds' : 'BENCH_ROUNDS');
  // One part alone: --x-only on the command line, else BENCH_ONLY=x.
  const parts = ['bvh', 'gltf', 'raster', 'lighting', 'instancing', 'output', 'gpu', 'browser'] as const;
  const flagged = parts.filter((p) => values[`${p}-only`] === true);
  if (flagged.length > 1) throw new Error(`--${flagged[0]}-only and --${flagged[1]}-only exclude each other`);
  const fromEnv = parts.find((p) => env.BENCH_ONLY?.toLowerCase() === p);
  const only = flagged[0] ?? fromEnv ?? null;
  for (const p of parts) {
    if (only === p && values[`no-${p}`]) throw new Error(`--${p}-only and --no-${p} exclude each other`);
  }
  const off = (name: string | undefined): boolean => name !== undefined && OFF.has(name.toLowerCase());
  const on = (p: (typeof parts)[number], variable: string | undefined): boolean => only === p || (only === null && !values[`no-${p}`] && !off(variable));
  const bvh = on('bvh', env.BENCH_BVH);
  const gltf = on('gltf', env.BENCH_GLTF);
  const raster = on('raster', env.BENCH_RASTER);
  const lighting = on('lighting', env.BENCH_LIGHTING);
  const instancing = on('instancing', env.BENCH_INSTANCING);
  const gpu = on('gpu', env.BENCH_GPU);
  const outputOn = !values['no-output'] && (values.output === true || (env.BENCH_OUTPUT !== undefined && !off(env.BENCH_OUTPUT)));
  const output = only === 'output' || (only === null && outputOn);
  const browserOn = !values['no-browser'] && (values.browser === true || (env.BENCH_BROWSER !== undefined && !off(env.BENCH_BROWSER)));
  const browser = only === 'browser' || (only === null && browserOn);
  return { baseline, rounds, bvh, gltf, raster, lighting, instancing, output, gpu, browser, pathTracer: only === null };
}
