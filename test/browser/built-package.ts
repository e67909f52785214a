// The ESM build the browser loads: dist/esm when it is at least as new as every source file,
// otherwise a fresh compile of src into a temporary folder (so a stale or missing dist never tests
// old code, and the test never deletes a dist another process may be using). The temporary folder
// sits under node_modules/.cache, so the build's imports of its dependencies resolve from the
// repo's node_modules, as dist's do, for any bundler.
import { spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, mkdtempSync, readdirSync, rmSync, statSync } from 'node:fs';
import { join } from 'node:path';

function newestMtime(dir: string): number {
  let newest = 0;
  for (const entry of readdirSync(dir, { withFileTypes: true })) {
    const path = join(dir, entry.name);
    newest = Math.max(newest, entry.isDirectory() ? newestMtime(path) : statSync(path).mtimeMs);
  }
  return newest;
}

export function builtPackageDir(root: string): { dir: string; cleanup(): void } {
  const dist = join(root, 'dist/esm');
  const index = join(dist, 'index.js');
  if (existsSync(index) && statSync(index).mtimeMs >= newestMtime(join(root, 'src'))) return { dir: dist, cleanup: () => undefined };
  const cache = join(root, 'node_modules/.cache');
  mkdirSync(cache, { recursive: true });
  const out = mkdtempSync(join(cache, 'gpu-renderer-esm-'));
  const tsc = join(root, 'node_modules/typescript-7/bin/tsc');
  // Type errors elsewhere do not stop emission; a missing index.js does.
  spawnSync(process.execPath, [tsc, '-p', 'tsconfig.build.json', '--outDir', out, '--declaration', 'false', '--sourceMap', 'false'], { cwd: root, stdio: 'ignore' });
  if (!existsSync(join(out, 'index.js'))) {
    rmSync(out, { recursive: true, force: true });
    throw new Error('could not build the ESM package (tsc -p tsconfig.build.json emitted no index.js)');
  }
  return { dir: out, cleanup: () => rmSync(out, { recursive: true, force: true }) };
}
