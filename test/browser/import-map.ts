// Builds a browser import map for the package's runtime dependencies (and theirs), resolving each
// package's browser/ESM entry from its package.json, so the page can load the unbundled build.
import { readFileSync } from 'node:fs';
import { join } from 'node:path';

type Exports = string | { [condition: string]: Exports } | undefined;

function pickEntry(exports: Exports): string | undefined {
  if (typeof exports === 'string') return exports;
  if (!exports) return undefined;
  const dot = '.' in exports ? exports['.'] : exports;
  if (typeof dot === 'string') return dot;
  for (const condition of ['browser', 'import', 'default']) {
    const entry = dot && typeof dot === 'object' ? pickEntry(dot[condition]) : undefined;
    if (entry) return entry;
  }
  return undefined;
}

export function createImportMap(root: string): { imports: Record<string, string> } {
  const imports: Record<string, string> = {};
  const visit = (name: string): void => {
    if (name in imports) return;
    const pkg = JSON.parse(readFileSync(join(root, 'node_modules', name, 'package.json'), 'utf8')) as {
      exports?: Exports;
      module?: string;
      browser?: string | Record<string, unknown>;
      main?: string;
      dependencies?: Record<string, string>;
    };
    const entry = pickEntry(pkg.exports) ?? pkg.module ?? (typeof pkg.browser === 'string' ? pkg.browser : undefined) ?? pkg.main ?? 'index.js';
    imports[name] = `/node_modules/${name}/${entry.replace(/^\.\//, '')}`;
    for (const dep of Object.keys(pkg.dependencies ?? {})) visit(dep);
  };
  const rootPkg = JSON.parse(readFileSync(join(root, 'package.json'), 'utf8')) as { dependencies?: Record<string, string> };
  // `webgpu` is Dawn for Node.js; the package only imports it off the browser path.
  for (const dep of Object.keys(rootPkg.dependencies ?? {})) if (dep !== 'webgpu') visit(dep);
  return { imports };
}
