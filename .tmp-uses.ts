import ts from 'typescript';
import { readFileSync, readdirSync, statSync } from 'node:fs';
import { join, resolve, dirname } from 'node:path';
const roots = ['demo', 'test', 'bench', 'scripts', 'src/cli', 'src/farm'];
const files: string[] = [];
const walk = (d: string) => { for (const n of readdirSync(d)) { if (n === 'node_modules') continue; const p = join(d, n); const s = statSync(p); if (s.isDirectory()) walk(p); else if (/\.(ts|js|mjs)$/.test(n)) files.push(p); } };
roots.forEach(walk);
const idx = resolve('src/index.ts');
const uses = new Map<string, Set<string>>();
for (const f of files) {
  const sf = ts.createSourceFile(f, readFileSync(f, 'utf8'), ts.ScriptTarget.Latest, true);
  for (const st of sf.statements) {
    if (!ts.isImportDeclaration(st) && !ts.isExportDeclaration(st)) continue;
    const spec = st.moduleSpecifier && ts.isStringLiteral(st.moduleSpecifier) ? st.moduleSpecifier.text : '';
    const isRoot = spec === '@plasius/gpu-renderer' || (spec.startsWith('.') && resolve(dirname(f), spec) === idx);
    if (!isRoot) continue;
    const names: string[] = [];
    if (ts.isImportDeclaration(st)) {
      const nb = st.importClause?.namedBindings;
      if (nb && ts.isNamedImports(nb)) nb.elements.forEach(e => names.push((e.propertyName ?? e.name).text));
      else if (nb) names.push('*NS*');
    } else if (st.exportClause && ts.isNamedExports(st.exportClause)) st.exportClause.elements.forEach(e => names.push((e.propertyName ?? e.name).text)); else names.push('*STAR*');
    for (const n of names) { if (!uses.has(n)) uses.set(n, new Set()); uses.get(n)!.add(f); }
  }
}
const mode = process.argv[2];
for (const [n, fs] of [...uses].sort()) console.log(n, [...fs].map(f => f.split('/')[0]).filter((v,i,a)=>a.indexOf(v)===i).join(','), mode === 'v' ? [...fs].join(' ') : '');
