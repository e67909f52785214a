// Builds the package: dist/esm (ES modules + .d.ts) and dist/cjs (CommonJS + .d.ts) with
// TypeScript 7, makes the CLI executable, then derives dist/browser from dist/esm (the "browser"
// export condition: see scripts/browser-build). Run through `npm run build` (which regenerates the
// embedded WGSL first).
import { spawnSync } from 'node:child_process';
import { chmodSync, existsSync, mkdirSync, readdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { buildBrowserDist } from './browser-build/index.ts';

const root = fileURLToPath(new URL('..', import.meta.url));
const dist = join(root, 'dist');
const tsc = join(root, 'node_modules/typescript-7/bin/tsc');

function compile(project: string): void {
  const started = performance.now();
  const result = spawnSync(process.execPath, [tsc, '-p', project], { cwd: root, stdio: 'inherit' });
  if (result.status !== 0) {
    console.error(`build: tsc -p ${project} failed (exit ${result.status ?? result.signal})`);
    process.exit(1);
  }
  console.log(`build: ${project} (${((performance.now() - started) / 1000).toFixed(1)}s)`);
}

rmSync(dist, { recursive: true, force: true });
compile('tsconfig.build.json');
compile('tsconfig.cjs.json');

// The root package.json says "type": "module"; this marks dist/cjs/**/*.js as CommonJS. It is also
// the package scope of those files, so it maps the OIDN weights' subpath imports itself, to shims
// that require the package's one copy (weights/oidn: ES modules, which require() loads).
const weightModules = readdirSync(join(root, 'weights/oidn')).filter((f) => f.endsWith('.js'));
writeFileSync(join(dist, 'cjs/package.json'), `${JSON.stringify({ type: 'commonjs', imports: { '#oidn-weights/*': './oidn-weights/*' } }, null, 2)}\n`);
mkdirSync(join(dist, 'cjs/oidn-weights'), { recursive: true });
for (const file of weightModules) writeFileSync(join(dist, 'cjs/oidn-weights', file), `module.exports = require('../../../weights/oidn/${file}');\n`);

// The package "bin": an ES module with a shebang, executable.
const cli = join(dist, 'esm/cli/main.js');
if (!existsSync(cli)) {
  console.error(`build: ${cli} was not emitted`);
  process.exit(1);
}
const shebang = '#!/usr/bin/env node';
const text = readFileSync(cli, 'utf8');
if (!text.startsWith(shebang)) writeFileSync(cli, `${shebang}\n${text}`);
chmodSync(cli, 0o755);

const started = performance.now();
const browser = await buildBrowserDist({ root, esmDir: join(dist, 'esm'), outDir: join(dist, 'browser') });
const vendored = Object.entries(browser.vendor.files).map(([file, bytes]) => `${file} ${(bytes / 1024).toFixed(0)} KiB`);
console.log(`build: dist/browser: ${browser.modules.modules.length} modules of dist/esm, ${vendored.join(', ')} (${((performance.now() - started) / 1000).toFixed(1)}s)`);

console.log('build: dist/esm, dist/cjs, dist/esm/cli/main.js (executable), dist/browser');
