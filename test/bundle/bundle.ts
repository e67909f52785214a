// Bundling the built package as a consumer's bundler would: a throwaway project whose
// node_modules/@plasius/gpu-renderer is this package (its package.json and its ESM build, fresh
// from src when dist is stale), bundled by esbuild for the browser. Resolution goes through the
// package's own `exports`, so the test sees what an installed copy gives a bundler.
import { cpSync, mkdirSync, mkdtempSync, realpathSync, rmSync, symlinkSync } from 'node:fs';
import { isBuiltin } from 'node:module';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import type { BuildOptions, Metafile, Plugin } from 'esbuild';
import { builtPackageDir } from '../browser/built-package.ts';

export const repoRoot = fileURLToPath(new URL('../..', import.meta.url));
export const consumerDir = fileURLToPath(new URL('./consumer/', import.meta.url));

export interface ConsumerProject {
  /** The project folder; its node_modules holds the package, src/ the consumer's files. */
  dir: string;
  /** The package's ESM entry as the bundler resolves it. */
  packageEntry: string;
  /** The real folder of the package's ESM build (bundlers resolve the symlink to it). */
  builtDir: string;
  cleanup(): void;
}

export function createConsumerProject(): ConsumerProject {
  const built = builtPackageDir(repoRoot);
  const dir = mkdtempSync(join(tmpdir(), 'gpu-renderer-consumer-'));
  const pkg = join(dir, 'node_modules/@plasius/gpu-renderer');
  mkdirSync(join(pkg, 'dist'), { recursive: true });
  cpSync(join(repoRoot, 'package.json'), join(pkg, 'package.json'));
  symlinkSync(built.dir, join(pkg, 'dist/esm'), 'dir');
  cpSync(consumerDir, join(dir, 'src'), { recursive: true });
  return {
    dir,
    packageEntry: join(pkg, 'dist/esm/index.js'),
    builtDir: realpathSync(built.dir),
    cleanup: () => {
      rmSync(dir, { recursive: true, force: true });
      built.cleanup();
    },
  };
}

/** What a consumer's esbuild configuration must leave external today (see esbuild-consumer.test.ts). */
export const consumerExternals = ['mikktspace', 'node:fs', 'node:path'];

/** The metafile inputs (paths relative to the project) that lie in the package's ESM build. */
export function packageInputs(project: ConsumerProject, metafile: Metafile): string[] {
  return Object.keys(metafile.inputs).filter((p) => resolve(project.dir, p).startsWith(project.builtDir));
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
  return { edges: edges.filter((e) => e.kind === 'import-statement'), metafile: result.metafile! };
}
