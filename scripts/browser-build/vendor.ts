// The vendored dependencies of the browser build (see vendored.ts), bundled with esbuild into
// dist/browser/vendor, each a self-contained ES module (their own small dependencies included, so
// the browser build imports nothing a consumer's install might not hoist):
// - @gltf-transform/core with node:fs and node:path replaced by a module that fails on import:
//   only NodeIO imports them, and NodeIO cannot work in a browser (WebIO is what the loader uses);
// - @gltf-transform/extensions, importing that copy of core;
// - mikktspace: its wasm-bindgen glue around its WebAssembly, inlined (mikktspace-entry.js).
import { readFileSync, readdirSync, writeFileSync } from 'node:fs';
import { createRequire, isBuiltin } from 'node:module';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import type { BuildOptions, Metafile, Plugin } from 'esbuild';
import { noticesFile, vendoredModules } from './vendored.ts';

const mikktspaceEntry = fileURLToPath(new URL('./mikktspace-entry.js', import.meta.url));

interface PackageInfo {
  name: string;
  version: string;
  license: string;
  dir: string;
}

export interface VendorReport {
  /** Output file (relative to the browser build) -> bytes. */
  files: Record<string, number>;
  /** Every package whose code was bundled, with version and licence. */
  packages: PackageInfo[];
}

/** The package folder of `name` as Node resolves it from `from` (a file or folder path). */
function packageDir(from: string, name: string): string {
  const require = createRequire(join(from, 'noop.js'));
  let dir = dirname(require.resolve(name));
  while (!readdirSync(dir).includes('package.json') || (JSON.parse(readFileSync(join(dir, 'package.json'), 'utf8')) as { name?: string }).name !== name) {
    if (dirname(dir) === dir) throw new Error(`cannot find the package folder of ${name}`);
    dir = dirname(dir);
  }
  return dir;
}

function readPackage(dir: string): PackageInfo & { module?: string; main?: string } {
  const pkg = JSON.parse(readFileSync(join(dir, 'package.json'), 'utf8')) as { name: string; version: string; license: string; module?: string; main?: string };
  return { ...pkg, dir };
}

/** Node built-ins imported dynamically become a module that throws when loaded; static imports fail the build. */
function stubNodeBuiltins(): Plugin {
  return {
    name: 'stub-node-builtins',
    setup(build) {
      build.onResolve({ filter: /.*/ }, (args) => {
        if (!isBuiltin(args.path)) return undefined;
        if (args.kind !== 'dynamic-import') return { errors: [{ text: `${args.importer} imports the Node.js built-in ${args.path} statically` }] };
        return { path: args.path, namespace: 'node-builtin-stub' };
      });
      build.onLoad({ filter: /.*/, namespace: 'node-builtin-stub' }, (args) => ({
        contents: `throw new Error(${JSON.stringify(`${args.path} is not available in a browser (@plasius/gpu-renderer's browser build; @gltf-transform's NodeIO needs Node.js, WebIO reads in browsers)`)});\n`,
        loader: 'js',
      }));
    },
  };
}

function exactly(specifier: string): RegExp {
  return new RegExp(`^${specifier.replace(/[.*+?^${}()|[\]\\]/g, '\\$&')}$`);
}

/** Resolves `specifier` to an external relative import (`./file.js` beside the output). */
function redirect(specifier: string, to: string): Plugin {
  return { name: `redirect ${specifier}`, setup: (build) => build.onResolve({ filter: exactly(specifier) }, () => ({ path: to, external: true })) };
}

/** Resolves `specifier` to the file `path`, bundled. */
function aliasFile(specifier: string, path: string): Plugin {
  return { name: `alias ${specifier}`, setup: (build) => build.onResolve({ filter: exactly(specifier) }, () => ({ path })) };
}

/**
 * mikktspace's `import * as wasm from './x_bg.wasm'` and the entry's `mikktspace-wasm` resolve to
 * one generated module: the WebAssembly bytes (base64) and a live binding per export, which
 * `bindWasmExports` sets once the module is instantiated. The bytes are those of the package's
 * Node.js build (its `main`), the very module Node runs, so both produce the same tangents; the
 * glue of the package's bundler build works with it (same exports, same imports by name).
 */
function mikktspaceWasm(nodeWasmPath: string): Plugin {
  return {
    name: 'mikktspace-wasm',
    setup(build) {
      build.onResolve({ filter: /^mikktspace-wasm$|\.wasm$/ }, () => ({ path: nodeWasmPath, namespace: 'mikktspace-wasm' }));
      build.onLoad({ filter: /.*/, namespace: 'mikktspace-wasm' }, (args) => {
        const bytes = readFileSync(args.path);
        const names = WebAssembly.Module.exports(new WebAssembly.Module(bytes)).map((e) => e.name);
        for (const name of names) if (!/^[A-Za-z_$][\w$]*$/.test(name)) throw new Error(`mikktspace wasm export ${name} is not an identifier`);
        return {
          contents:
            `export const wasmBase64 = ${JSON.stringify(bytes.toString('base64'))};\n` +
            `export let ${names.join(', ')};\n` +
            `export function bindWasmExports(exports) {\n${names.map((n) => `  ${n} = exports.${n};\n`).join('')}}\n`,
          loader: 'js',
        };
      });
    },
  };
}

/** The licence text a package ships (LICENSE, LICENSE.md, ...). */
function licenceText(pkg: PackageInfo): string {
  const file = readdirSync(pkg.dir).find((f) => /^licen[cs]e(\.md|\.txt)?$/i.test(f));
  if (file === undefined) throw new Error(`${pkg.name} ships no LICENSE file`);
  return readFileSync(join(pkg.dir, file), 'utf8').trim();
}

/** Packages (by folder) whose files make up a bundle's inputs. */
function bundledPackages(metafile: Metafile, cwd: string): string[] {
  const dirs = new Set<string>();
  for (const input of Object.keys(metafile.inputs)) {
    // Inputs of a plugin namespace read `namespace:path`.
    const path = /^[\w-]+:/.test(input) ? input.slice(input.indexOf(':') + 1) : join(cwd, input);
    const match = /^(.*node_modules\/(?:@[^/]+\/)?[^/]+)\//.exec(path);
    if (match) dirs.add(match[1]!);
  }
  return [...dirs];
}

/** Bundles the vendored dependencies into `outDir`/vendor; dependencies resolve from `root`. */
export async function buildVendorModules(root: string, outDir: string): Promise<VendorReport> {
  const { build } = await import('esbuild');
  const common: BuildOptions = {
    bundle: true,
    format: 'esm',
    platform: 'browser',
    target: 'es2022',
    absWorkingDir: root,
    metafile: true,
    write: true,
    logLevel: 'silent',
    legalComments: 'inline',
  };
  const mikktspace = readPackage(packageDir(root, 'mikktspace'));
  if (mikktspace.module === undefined || mikktspace.main === undefined) throw new Error('mikktspace has no "module" or "main" build');
  const nodeWasm = readdirSync(dirname(join(mikktspace.dir, mikktspace.main))).filter((f) => f.endsWith('.wasm'));
  if (nodeWasm.length !== 1) throw new Error(`mikktspace's Node build has ${nodeWasm.length} .wasm files`);

  const builds: Array<{ specifier: string; options: BuildOptions }> = [
    { specifier: '@gltf-transform/core', options: { entryPoints: ['@gltf-transform/core'], plugins: [stubNodeBuiltins()] } },
    { specifier: '@gltf-transform/extensions', options: { entryPoints: ['@gltf-transform/extensions'], plugins: [redirect('@gltf-transform/core', './gltf-transform-core.js'), stubNodeBuiltins()] } },
    {
      specifier: 'mikktspace',
      options: {
        entryPoints: [mikktspaceEntry],
        plugins: [aliasFile('mikktspace-glue', join(mikktspace.dir, mikktspace.module)), mikktspaceWasm(join(dirname(join(mikktspace.dir, mikktspace.main)), nodeWasm[0]!)), stubNodeBuiltins()],
      },
    },
  ];
  const report: VendorReport = { files: {}, packages: [] };
  const packageDirs = new Set<string>();
  for (const { specifier, options } of builds) {
    const file = vendoredModules[specifier]!;
    const result = await build({
      ...common,
      ...options,
      outfile: join(outDir, file),
      banner: { js: `/*! ${specifier}, bundled for @plasius/gpu-renderer's browser build; licences: ${noticesFile.replace('vendor/', './')} */` },
    });
    if (result.errors.length > 0) throw new Error(result.errors.map((e) => e.text).join('\n'));
    for (const dir of bundledPackages(result.metafile!, root)) packageDirs.add(dir);
    const output = Object.values(result.metafile!.outputs)[0]!;
    report.files[file] = output.bytes;
  }
  report.packages = [...packageDirs].map(readPackage).map(({ name, version, license, dir }) => ({ name, version, license, dir })).sort((a, b) => a.name.localeCompare(b.name));
  const notices = report.packages.map((p) => `${p.name}@${p.version} (${p.license})\n\n${licenceText(p)}\n`).join(`\n${'-'.repeat(78)}\n\n`);
  writeFileSync(join(outDir, noticesFile), `Third-party code bundled in dist/browser/vendor of @plasius/gpu-renderer:\n\n${notices}`);
  return report;
}
