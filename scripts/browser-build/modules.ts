// The package's own modules in the browser build: every module the ESM entry reaches (static and
// dynamic imports), copied from dist/esm byte for byte except for import specifiers, so browsers
// run the very code TypeScript emitted for Node. Two kinds of edit, found with es-module-lexer:
// - imports of a vendored dependency (vendored.ts) point at its copy in dist/browser/vendor;
// - dynamic imports whose specifier is computed at run time (the Node-only paths: Dawn, node:fs,
//   draco3dgltf, ...) get `webpackIgnore` / `@vite-ignore` comments, so bundlers neither warn
//   about nor try to resolve them (webpack would otherwise make an empty context module).
// A Node.js built-in imported by name fails the build (browser code must not name one), and so
// does import.meta (assets found through it would not be copied). Package subpath imports
// (`#oidn-weights/...`: the OIDN weights, one copy in the package) stay as they are: bundlers
// resolve them through the package's "imports".
import { copyFileSync, existsSync, mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { isBuiltin } from 'node:module';
import { dirname, join, posix, relative, resolve, sep } from 'node:path';
import { init, parse } from 'es-module-lexer';
import { vendoredModules } from './vendored.ts';

const IGNORE_COMMENT = '/* webpackIgnore: true */ /* @vite-ignore */ ';

export interface ModuleCopyReport {
  /** Module paths relative to the output folder, in the order they were reached. */
  modules: string[];
  /** `module -> specifier` for each import redirected to a vendored copy. */
  redirected: string[];
  /** Modules whose computed dynamic imports got the bundler-ignore comments. */
  annotated: string[];
}

interface Edit {
  start: number;
  end: number;
  text: string;
}

function toPosix(path: string): string {
  return path.split(sep).join('/');
}

/** `target` (relative to the output root) as a specifier from the module at `from` (also relative). */
function relativeSpecifier(from: string, target: string): string {
  const path = posix.relative(posix.dirname(toPosix(from)), target);
  return path.startsWith('.') ? path : `./${path}`;
}

/**
 * Copies the module graph of `esmDir/index.js` into `outDir` (same layout, with source maps),
 * applying the edits above; returns what it did.
 */
export async function copyBrowserModules(esmDir: string, outDir: string): Promise<ModuleCopyReport> {
  await init;
  const report: ModuleCopyReport = { modules: [], redirected: [], annotated: [] };
  const queue = ['index.js'];
  const seen = new Set(queue);
  while (queue.length > 0) {
    const path = queue.shift()!;
    const source = readFileSync(join(esmDir, path), 'utf8');
    const [imports] = parse(source, path);
    const edits: Edit[] = [];
    for (const record of imports) {
      // `new URL('./asset', import.meta.url)` would name a file this copy does not carry.
      if (record.d === -2) throw new Error(`${path}: uses import.meta, which the browser build does not support (it copies modules only)`);
      const dynamic = record.d >= 0;
      const specifier = record.n;
      if (specifier === undefined) {
        if (!dynamic) throw new Error(`${path}: an import the lexer could not read`);
        edits.push({ start: record.s, end: record.s, text: IGNORE_COMMENT });
        if (!report.annotated.includes(path)) report.annotated.push(path);
        continue;
      }
      if (specifier.startsWith('.')) {
        const target = toPosix(relative(esmDir, resolve(esmDir, dirname(path), specifier)));
        if (!target.endsWith('.js') || !existsSync(join(esmDir, target))) throw new Error(`${path}: imports ${specifier}, which dist/esm does not have`);
        if (!seen.has(target)) {
          seen.add(target);
          queue.push(target);
        }
        continue;
      }
      if (isBuiltin(specifier)) throw new Error(`${path}: imports the Node.js built-in ${specifier} by name; browser code must reach Node-only modules through computed specifiers`);
      const vendored = vendoredModules[specifier];
      if (vendored === undefined) continue;
      const replacement = relativeSpecifier(path, vendored);
      // A static import's range is the specifier's text; a dynamic import's includes the quotes.
      edits.push(dynamic ? { start: record.s, end: record.e, text: JSON.stringify(replacement) } : { start: record.s, end: record.e, text: replacement });
      report.redirected.push(`${path} -> ${specifier}`);
    }
    let text = source;
    for (const edit of edits.sort((a, b) => b.start - a.start)) text = text.slice(0, edit.start) + edit.text + text.slice(edit.end);
    const out = join(outDir, path);
    mkdirSync(dirname(out), { recursive: true });
    writeFileSync(out, text);
    // The maps name the TypeScript sources relative to the module, which dist/browser keeps as
    // dist/esm has it; an edit shifts columns on its own line only.
    if (existsSync(join(esmDir, `${path}.map`))) copyFileSync(join(esmDir, `${path}.map`), `${out}.map`);
    report.modules.push(path);
  }
  return report;
}
