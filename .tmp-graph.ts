import ts from 'typescript';
import { readFileSync, readdirSync, statSync } from 'node:fs';
import { join, resolve, dirname, relative } from 'node:path';
const files: string[] = [];
const walk = (d: string) => { for (const n of readdirSync(d)) { const p = join(d, n); if (statSync(p).isDirectory()) walk(p); else if (n.endsWith('.ts')) files.push(p); } };
walk('src');
const counts = new Map<string, number>();
const folder = (p: string) => { const r = relative('src', p).split('/'); return r.length === 1 ? '.' : r[0]; };
for (const f of files) {
  const info = ts.preProcessFile(readFileSync(f, 'utf8'), true, true);
  for (const imp of info.importedFiles) {
    if (!imp.fileName.startsWith('.')) continue;
    const target = resolve(dirname(f), imp.fileName);
    const a = folder(f), b = folder(relative('.', target));
    if (a === b) continue;
    const key = `${a} -> ${b}`;
    counts.set(key, (counts.get(key) ?? 0) + 1);
    if (process.argv[2] && key === process.argv[2]) console.log('  ', f, imp.fileName);
  }
}
if (!process.argv[2]) for (const [k, v] of [...counts].sort()) console.log(k, v);
