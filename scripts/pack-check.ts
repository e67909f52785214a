// Checks the published package as a consumer sees it: `npm pack`, install the tarball into a fresh
// project, then import it as ESM and require it as CommonJS on Node 24, bundle it for browsers
// with esbuild and webpack with no configuration (the "browser" condition: dist/browser), and
// type-check consumer code against its .d.ts (module/moduleResolution nodenext, both the import
// and require conditions). Run after `npm run build` (`npm run pack:check` does both).
import { spawnSync, type SpawnSyncReturns } from 'node:child_process';
import { mkdirSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import type { Stats } from 'webpack';
import { vendoredModules } from './browser-build/index.ts';
import { noticesFile } from './browser-build/vendored.ts';
import { unlinkedFiles, unpackedLinks } from './markdown-links.ts';

const root = fileURLToPath(new URL('..', import.meta.url));
const node = join(root, 'node_modules/.bin/node');
const tsc = join(root, 'node_modules/typescript-7/bin/tsc');
const pkg = JSON.parse(readFileSync(join(root, 'package.json'), 'utf8')) as { name: string; version: string; repository?: { url?: string }; homepage?: string; bugs?: { url?: string } };

const failures: string[] = [];
const summary: string[] = [];

function sh(command: string, args: string[], cwd: string): SpawnSyncReturns<string> {
  return spawnSync(command, args, { cwd, encoding: 'utf8', env: { ...process.env, npm_config_update_notifier: 'false' } });
}

function step(name: string, result: SpawnSyncReturns<string>): string {
  if (result.status !== 0) {
    failures.push(`${name} failed (exit ${result.status ?? result.signal})\n${result.stdout}${result.stderr}`.trimEnd());
    return '';
  }
  summary.push(`ok   ${name}`);
  return result.stdout;
}

function check(name: string, ok: boolean, detail = ''): void {
  if (ok) summary.push(`ok   ${name}`);
  else failures.push(`${name}${detail ? `: ${detail}` : ''}`);
}

// Exports every entry point must have (values), and types consumer code must be able to name.
const requiredExports = ['supportsWebGpu', 'GpuRendererError', 'isGpuRendererError', 'acquireGpuDevice', 'rendererWavefrontComputeWorkgroupSize', 'encodePng', 'applyToneMapping'];

/** Bundles a browser app that renders and loads glTF, in `consumer`, with esbuild and with webpack. */
async function checkBrowserBundles(consumer: string): Promise<void> {
  mkdirSync(join(consumer, 'app'));
  writeFileSync(
    join(consumer, 'app/main.js'),
    `import { createWavefrontPathTracingComputeRenderer, loadGltfScene, createCornellBoxScene } from '${pkg.name}';\n` +
      `window.app = { createWavefrontPathTracingComputeRenderer, loadGltfScene, createCornellBoxScene };\n`,
  );
  const installed = join(consumer, 'node_modules', pkg.name, 'dist');
  const { build } = await import('esbuild');
  try {
    const result = await build({ entryPoints: [join(consumer, 'app/main.js')], bundle: true, platform: 'browser', format: 'esm', splitting: true, outdir: join(consumer, 'out-esbuild'), absWorkingDir: consumer, metafile: true, logLevel: 'silent' });
    const inputs = Object.keys(result.metafile.inputs).map((p) => join(consumer, p));
    check('esbuild bundles it for the browser with no configuration', result.warnings.length === 0, result.warnings.map((w) => w.text).join('; '));
    check('esbuild resolves the browser build (dist/browser, vendor/mikktspace.js)', inputs.includes(join(installed, 'browser/index.js')) && inputs.includes(join(installed, 'browser', vendoredModules.mikktspace!)) && !inputs.some((p) => p.startsWith(join(installed, 'esm'))));
  } catch (error) {
    failures.push(`esbuild bundles it for the browser with no configuration: ${String(error)}`);
  }
  const { default: webpack } = await import('webpack');
  const stats = await new Promise<Stats | undefined>((resolve) => {
    webpack({ mode: 'development', devtool: false, context: consumer, entry: './app/main.js', output: { path: join(consumer, 'out-webpack') } }, (error, result) => {
      if (error) failures.push(`webpack: ${String(error)}`);
      resolve(result);
    });
  });
  if (stats) {
    const info = stats.toJson({ all: false, errors: true, warnings: true });
    const problems = [...(info.errors ?? []), ...(info.warnings ?? [])].map((e) => e.message.split('\n')[0]);
    check('webpack 5 bundles it for the web with no configuration', problems.length === 0, problems.join('; '));
  }
}

const work = mkdtempSync(join(tmpdir(), 'gpu-renderer-pack-'));
try {
  // 1. The tarball and what it holds.
  const packed = step('npm pack', sh('npm', ['pack', '--json', '--pack-destination', work], root));
  if (!packed) throw new Error('npm pack failed');
  const info = (JSON.parse(packed) as { filename: string; size: number; unpackedSize: number; files: { path: string }[] }[])[0];
  const files = new Set(info.files.map((f) => f.path));
  const browserFiles = ['dist/browser/index.js', ...[...Object.values(vendoredModules), noticesFile].map((f) => `dist/browser/${f}`)];
  for (const f of ['package.json', 'README.md', 'weights/oidn/rt_hdr_alb_nrm.0.js', 'weights/oidn/rt_hdr.0.js', 'weights/oidn/LICENSE.txt', 'dist/esm/index.js', 'dist/esm/index.d.ts', 'dist/cjs/index.js', 'dist/cjs/index.d.ts', 'dist/cjs/package.json', 'dist/esm/cli/main.js', ...browserFiles]) {
    check(`tarball has ${f}`, files.has(f));
  }
  // weights/oidn: the OIDN weight modules (not their .tza sources), shared by every build; the
  // documentation the README links (docs/, demo/README.md), so its links work from node_modules.
  const documentation = (f: string): boolean => /^docs\/[^/]+\.md$/.test(f) || /^docs\/images\/[^/]+\.png$/.test(f) || f === 'demo/README.md';
  const stray = [...files].filter((f) => !f.startsWith('dist/') && !/^weights\/oidn\/[^/]+\.(js|d\.ts|txt|md)$/.test(f) && !documentation(f) && !['package.json', 'README.md', 'LICENSE'].includes(f));
  check('tarball holds only dist/, weights/oidn/ modules, README.md and the pages it links, package.json', stray.length === 0, stray.join(', '));
  // The packed pages are the repository's files (npm pack copies them as they are).
  const readPacked = (path: string): string => readFileSync(join(root, path), 'utf8');
  const broken = unpackedLinks(files, readPacked);
  check('every relative link of the packed Markdown pages names a packed file', broken.length === 0, broken.join(', '));
  const unlinked = unlinkedFiles(files, readPacked, 'README.md', documentation);
  check('every packed page and image is reached by links from README.md', unlinked.length === 0, unlinked.join(', '));
  check('package.json names the repository, homepage and issue tracker', Boolean(pkg.repository?.url && pkg.homepage && pkg.bugs?.url));
  const tarball = join(work, info.filename);

  // 2. A clean consumer project with the tarball installed (runtime deps from the registry cache).
  const consumer = join(work, 'consumer');
  mkdirSync(consumer);
  writeFileSync(join(consumer, 'package.json'), JSON.stringify({ name: 'pack-check-consumer', private: true, version: '0.0.0' }, null, 2));
  const installed = step(
    'npm install <tarball> in a clean project',
    sh('npm', ['install', '--prefer-offline', '--no-audit', '--no-fund', '--ignore-scripts=false', tarball], consumer),
  );
  if (installed === '' && failures.length > 0) throw new Error('install failed');

  // 3. Runtime: ESM import and CommonJS require on Node 24.
  const exportsList = JSON.stringify(requiredExports);
  writeFileSync(
    join(consumer, 'esm.mjs'),
    `import * as r from '${pkg.name}';\n` +
      `const missing = ${exportsList}.filter((k) => !(k in r));\n` +
      `if (missing.length) { console.error('missing ESM exports: ' + missing.join(', ')); process.exit(1); }\n` +
      `const e = new r.GpuRendererError('INVALID_OPTION', 'bad', { field: 'width' });\n` +
      `if (!r.isGpuRendererError(e) || e.message !== 'width: bad') process.exit(1);\n` +
      `if (typeof r.supportsWebGpu !== 'function') process.exit(1);\n` +
      `console.log(Object.keys(r).length);\n`,
  );
  writeFileSync(
    join(consumer, 'cjs.cjs'),
    `const r = require('${pkg.name}');\n` +
      `const missing = ${exportsList}.filter((k) => !(k in r));\n` +
      `if (missing.length) { console.error('missing CJS exports: ' + missing.join(', ')); process.exit(1); }\n` +
      `if (require.resolve('${pkg.name}').indexOf('/dist/cjs/') < 0) { console.error('require resolved ' + require.resolve('${pkg.name}')); process.exit(1); }\n` +
      `const e = new r.GpuRendererError('INVALID_OPTION', 'bad');\n` +
      `if (!(e instanceof Error) || e.code !== 'INVALID_OPTION') process.exit(1);\n` +
      `console.log(Object.keys(r).length);\n`,
  );
  const esmCount = step('ESM import on Node 24', sh(node, ['esm.mjs'], consumer)).trim();
  const cjsCount = step('CommonJS require on Node 24', sh(node, ['cjs.cjs'], consumer)).trim();
  check('ESM and CommonJS entries export the same names', esmCount !== '' && esmCount === cjsCount, `${esmCount} vs ${cjsCount}`);

  // The browser build loads in Node too: the same export names as the ESM entry.
  writeFileSync(join(consumer, 'browser.mjs'), `const r = await import('./node_modules/${pkg.name}/dist/browser/index.js');\nconsole.log(Object.keys(r).length);\n`);
  const browserCount = step('browser build imported on Node 24', sh(node, ['browser.mjs'], consumer)).trim();
  check('browser and ESM entries export the same number of names', browserCount !== '' && browserCount === esmCount, `${browserCount} vs ${esmCount}`);

  // 4. Browser bundles with no configuration: esbuild (platform browser) and webpack (web target)
  // both resolve the browser entry and bundle it, glTF loading with MikkTSpace included.
  await checkBrowserBundles(consumer);

  // The bin: installed into node_modules/.bin, executable, runs --help.
  const help = sh(node, [join(consumer, 'node_modules/.bin/gpu-renderer'), '--help'], consumer);
  check('bin gpu-renderer --help', help.status === 0 && help.stdout.includes('Usage: gpu-renderer'), help.stderr);

  // 5. Types: consumer code type-checks against the shipped .d.ts through both conditions.
  const typeTest = (header: string): string =>
    `${header}\n` +
    `const err: GpuRendererError = new GpuRendererError('INVALID_SCENE_FILE', 'x', { field: 'meshes[0]' });\n` +
    `const code: GpuRendererErrorCode = err.code;\n` +
    `const size: number = rendererWavefrontComputeWorkgroupSize;\n` +
    `const ok: Promise<boolean> = supportsWebGpu();\n` +
    `const scene: WavefrontSceneDescription = { camera: { position: [0, 0, 3], target: [0, 0, 0] }, meshes: [{ positions: [0, 0, 0, 1, 0, 0, 0, 1, 0] }] };\n` +
    `const mode: WavefrontToneMapping = 'aces';\n` +
    `// @ts-expect-error an unknown error code must not type-check\n` +
    `new GpuRendererError('NOT_A_CODE', 'x');\n` +
    `// @ts-expect-error an unknown tone mapping must not type-check\n` +
    `const bad: WavefrontToneMapping = 'filmic';\n` +
    `export { code, size, ok, scene, mode, bad };\n`;
  const names = 'GpuRendererError, rendererWavefrontComputeWorkgroupSize, supportsWebGpu, type GpuRendererErrorCode, type WavefrontSceneDescription, type WavefrontToneMapping';
  writeFileSync(join(consumer, 'esm-types.mts'), typeTest(`import { ${names} } from '${pkg.name}';`));
  writeFileSync(join(consumer, 'cjs-types.cts'), typeTest(`import { ${names} } from '${pkg.name}';`));
  writeFileSync(
    join(consumer, 'tsconfig.json'),
    JSON.stringify(
      {
        compilerOptions: {
          strict: true,
          noEmit: true,
          target: 'es2022',
          // ES2025 (esnext) for Float16Array, which @gltf-transform/core's declarations (the
          // glTF loader's Document type) use.
          lib: ['esnext', 'dom'],
          module: 'nodenext',
          moduleResolution: 'nodenext',
          // TypeScript 7's lib.dom declares WebGPU itself (adding @webgpu/types would clash), and
          // skipLibCheck is off so the package's own .d.ts files are checked too.
          types: [],
          skipLibCheck: false,
        },
        files: ['esm-types.mts', 'cjs-types.cts'],
      },
      null,
      2,
    ),
  );
  step('consumer .d.ts type check (nodenext, import + require)', sh(node, [tsc, '-p', 'tsconfig.json'], consumer));
  summary.push(`     ${info.filename}: ${(info.size / 1024).toFixed(0)} KiB packed, ${(info.unpackedSize / 1024).toFixed(0)} KiB unpacked, ${files.size} files, ${esmCount} exports`);
} catch (error) {
  if (failures.length === 0) failures.push(String(error));
} finally {
  rmSync(work, { recursive: true, force: true });
}

console.log(`pack:check ${pkg.name}@${pkg.version}`);
for (const line of summary) console.log(line);
if (failures.length > 0) {
  for (const f of failures) console.error(`FAIL ${f}`);
  process.exit(1);
}
console.log('pack:check passed');
