// The browser build's root module. src/index.ts names every public export (`export { a, b } from
// './scene/index.ts'`, a statement per subsystem); dist/browser/index.js reaches the same names
// through `export * from './root/scene.js'`, where root/scene.js holds that statement as written.
//
// Why: esbuild assigns modules to code-splitting chunks by following every import record and
// every part dependency of each live module, used or not (evanw/esbuild#3531). A named re-export
// makes the root live in every app that imports anything from the package, and the root's export
// list depends on the module defining each public name; so every such module that a lazy chunk
// also uses (the glTF reader, the codecs) lands in a chunk shared with that lazy chunk and loaded at
// start: an app importing only `isGpuRendererError` loaded 79 KiB of scene, lighting and I/O code.
// An `export *` is resolved through without making the root live, so esbuild follows only the
// statements of the names an app imports. Rollup and webpack tree-shake either form alike.
//
// The statements are moved verbatim (only their specifiers gain a `../`), so the root's names are
// src/index.ts's names; the split fails the build on anything else in the root (a local export,
// an import, a name exported twice), which `export *` would hide or make ambiguous.
import { existsSync, mkdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { join, posix } from 'node:path';
import { init, parse } from 'es-module-lexer';

export interface RootSplitReport {
  /** The modules the root re-exports, relative to the output folder (`root/scene.js`, ...). */
  modules: string[];
  /** The names the root exports, in source order. */
  names: string[];
}

/** `root/<subsystem>.js` for a re-export of `./<subsystem>/index.js` (`root/index.js` for a module at the top). */
function groupModule(specifier: string): string {
  const dir = posix.dirname(posix.normalize(specifier));
  return `root/${dir === '.' ? posix.basename(specifier, '.js') : dir.replaceAll('/', '-')}.js`;
}

/** Rewrites `outDir/index.js` (a copy of dist/esm/index.js) into `export *` lines over root/*.js; returns what it wrote. */
export async function splitRootModule(outDir: string): Promise<RootSplitReport> {
  await init;
  const path = join(outDir, 'index.js');
  const source = readFileSync(path, 'utf8');
  const [imports, exports] = parse(source, 'index.js');
  const statements = imports.map((record) => {
    const text = source.slice(record.ss, record.se);
    if (record.d !== -1 || record.n === undefined || !text.startsWith('export') || !record.n.startsWith('./')) {
      throw new Error(`index.js: the root may only re-export by name from its own modules (\`export { a } from './x.js'\`), found: ${text}`);
    }
    // The statement with its semicolon (the lexer's range ends at the specifier).
    const end = source[record.se] === ';' ? record.se + 1 : record.se;
    return { start: record.ss, end, specifier: record.n, specifierStart: record.s - record.ss, specifierEnd: record.e - record.ss, text: source.slice(record.ss, end) };
  });
  const names = exports.map((e) => {
    if (!statements.some((s) => e.s >= s.start && e.e <= s.end)) throw new Error(`index.js: export ${e.n} is not a re-export; the root may only re-export by name`);
    return e.n;
  });
  const twice = names.filter((n, i) => names.indexOf(n) !== i);
  if (twice.length > 0) throw new Error(`index.js: ${twice.join(', ')} exported more than once`);

  // One module per statement, named by its subsystem (`root/io-2.js` for a second statement from io/).
  const modules: string[] = [];
  for (const s of statements) {
    const base = groupModule(s.specifier);
    let module = base;
    for (let n = 2; modules.includes(module); n++) module = base.replace(/\.js$/, `-${n}.js`);
    modules.push(module);
  }
  if (existsSync(join(outDir, 'root'))) throw new Error(`${join(outDir, 'root')} exists: the package has a root/ folder of its own, which the split would overwrite`);
  mkdirSync(join(outDir, 'root'));
  let text = '';
  let at = 0;
  statements.forEach((s, i) => {
    const moved = s.text.slice(0, s.specifierStart) + posix.join('..', s.specifier) + s.text.slice(s.specifierEnd);
    writeFileSync(join(outDir, modules[i]!), `${moved}\n`);
    text += `${source.slice(at, s.start)}export * from './${modules[i]!}';`;
    at = s.end;
  });
  text += source.slice(at);
  // The source map of the copy named the statements where tsc put them; the root no longer has them.
  text = text.replace(/\n\/\/# sourceMappingURL=\S+\s*$/, '\n');
  writeFileSync(path, text);
  if (existsSync(`${path}.map`)) rmSync(`${path}.map`);
  return { modules, names };
}
