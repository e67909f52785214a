// Bundling the built package as a consumer's bundler would: a throwaway project whose
// node_modules/@plasius/gpu-renderer is this package (its package.json, its ESM build, fresh from
// src when dist is stale, and the browser build derived from that ESM build by
// scripts/browser-build). Resolution goes through the package's own `exports`, so the test sees
// what an installed copy gives a bundler: the "browser" condition picks dist/browser.
import { cpSync, mkdirSync, mkdtempSync, realpathSync, rmSync, symlinkSync } from 'node:fs';
import { isBuiltin } from 'node:module';
import { tmpdir } from 'node:os';
import { join, resolve, sep } from 'node:path';
import { fileURLToPath } from 'node:url';
import type { BuildOptions, Metafile, Plugin } from 'esbuild';
import { buildBrowserDist, type BrowserBuildReport } from '../../scripts/browser-build/index.ts';
import { builtPackageDir } from '../browser/built-package.ts';

export const repoRoot = fileURLToPath(new URL('../..', import.meta.url));
export const consumerDir = fileURLToPath(new URL('./consumer/', import.meta.url));

export interface BuiltPackage {
  /** The real folder of the ESM build (dist/esm, or a fresh build of src). */
  esmDir: string;
  /** The real folder of the browser build made from it. */
  browserDir: string;
  report: BrowserBuildReport;
}

let built: Promise<BuiltPackage> | undefined;

/**
 * The ESM build and a browser build of it, made once per test process (the browser build always
 * fresh, so the tests check the current scripts/browser-build) and removed when the process exits.
 * Both sit under the repository, so their dependencies resolve from its node_modules.
 */
export function builtPackage(): Promise<BuiltPackage> {
  built ??= (async () => {
    const esm = builtPackageDir(repoRoot);
    const cache = join(repoRoot, 'node_modules/.cache');
    mkdirSync(cache, { recursive: true });
    const browserDir = mkdtempSync(join(cache, 'gpu-renderer-browser-'));
    process.once('exit', () => {
      rmSync(browserDir, { recursive: true, force: true });
      esm.cleanup();
    });
    const report = await buildBrowserDist({ root: repoRoot, esmDir: esm.dir, outDir: browserDir });
    return { esmDir: realpathSync(esm.dir), browserDir: realpathSync(browserDir), report };
  })();
  return built;
}

export interface ConsumerProject {
  /** The project folder; its node_modules holds the package, src/ the consumer's files. */
  dir: string;
  /** The package's ESM entry (what Node's "import" condition picks), inside the project. */
  packageEntry: string;
  /** The package's browser entry (the "browser" condition), inside the project. */
  browserEntry: string;
  /** The real folder of the package's ESM build (bundlers resolve the symlink to it). */
  builtDir: string;
  /** The real folder of the package's browser build. */
  browserDir: string;
  cleanup(): void;
}

export async function createConsumerProject(): Promise<ConsumerProject> {
  const pkgBuild = await builtPackage();
  const dir = mkdtempSync(join(tmpdir(), 'gpu-renderer-consumer-'));
  const pkg = join(dir, 'node_modules/@plasius/gpu-renderer');
  mkdirSync(join(pkg, 'dist'), { recursive: true });
  cpSync(join(repoRoot, 'package.json'), join(pkg, 'package.json'));
  symlinkSync(pkgBuild.esmDir, join(pkg, 'dist/esm'), 'dir');
  symlinkSync(pkgBuild.browserDir, join(pkg, 'dist/browser'), 'dir');
  // The OIDN weight modules the package's "#oidn-weights/*" imports name.
  symlinkSync(join(repoRoot, 'weights'), join(pkg, 'weights'), 'dir');
  cpSync(consumerDir, join(dir, 'src'), { recursive: true });
  return {
    dir,
    packageEntry: join(pkg, 'dist/esm/index.js'),
    browserEntry: join(pkg, 'dist/browser/index.js'),
    builtDir: pkgBuild.esmDir,
    browserDir: pkgBuild.browserDir,
    cleanup: () => rmSync(dir, { recursive: true, force: true }),
  };
}

/** The metafile inputs (paths relative to the project) that lie in the package's `build` ('esm' or 'browser'). */
export function packageInputs(project: ConsumerProject, metafile: Metafile, build: 'esm' | 'browser' = 'esm'): string[] {
  const root = (build === 'esm' ? project.builtDir : project.browserDir) + sep;
  return Object.keys(metafile.inputs).filter((p) => resolve(project.dir, p).startsWith(root));
}

/** esbuild options for a browser bundle in `project`; the package's own dependencies resolve from the repo. */
export function browserBuildOptions(project: ConsumerProject, options: BuildOptions): BuildOptions {
  return {
    bundle: true,
    platform: 'browser',
    format: 'esm',
    target: 'es2022',
    logLevel: 'silent',
    absWorkingDir: project.dir,
    ...options,
  };
}

export interface ImportEdge {
  importer: string;
  path: string;
  kind: string;
}

/**
 * An esbuild plugin that records every import of a Node.js built-in module (and of `webgpu`'s
 * Node-only Dawn binding) and leaves it external, so a whole graph can be listed in one build.
 */
export function recordNodeImports(edges: ImportEdge[]): Plugin {
  return {
    name: 'record-node-imports',
    setup(build) {
      build.onResolve({ filter: /.*/ }, (args) => {
        if (!isBuiltin(args.path) && args.path !== 'webgpu') return undefined;
        edges.push({ importer: args.importer, path: args.path, kind: args.kind });
        return { path: args.path, external: true };
      });
    },
  };
}

/** Node-only modules the module graph of `entry` imports statically (ESM import statements). */
export async function staticNodeImports(entry: string, options: BuildOptions = {}): Promise<{ edges: ImportEdge[]; metafile: Metafile }> {
  const { edges, metafile } = await nodeImports(entry, options);
  return { edges: edges.filter((e) => e.kind === 'import-statement'), metafile };
}

/** Every import of a Node-only module (any kind: static, dynamic, require) in the module graph of `entry`. */
export async function nodeImports(entry: string, options: BuildOptions = {}): Promise<{ edges: ImportEdge[]; metafile: Metafile }> {
  const { build } = await import('esbuild');
  const edges: ImportEdge[] = [];
  const result = await build({
    entryPoints: [entry],
    bundle: true,
    write: false,
    platform: 'browser',
    format: 'esm',
    logLevel: 'silent',
    metafile: true,
    outdir: join(tmpdir(), 'unused'),
    splitting: true,
    ...options,
    plugins: [recordNodeImports(edges), ...(options.plugins ?? [])],
  });
  return { edges, metafile: result.metafile! };
}
