// Renders the real-world assets of a SOURCES.tsv (name, repository, path, commit; the last row an
// HDRI) with the CLI, as a user would, and lays the renders out on one labelled contact sheet.
// The assets are read from a folder where each row was extracted as <name>/<path> (see
// shared/assets/README.md); nothing is downloaded. For each asset it records the CLI's warnings,
// notes, errors and invalid-sample count in a report next to the renders.
//
//   node scripts/real-assets/contact-sheet.ts --sources SOURCES.tsv --assets DIR --out DIR
//     [--sheet FILE.png] [--size 256] [--spp 32] [--columns 8] [--only NAME,NAME]
//
// Writes DIR/<name>.png, DIR/<name>.log (the CLI's stderr), DIR/report.md and the sheet
// (default DIR/contact-sheet.png).
import { spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, readdirSync, readFileSync, statSync, writeFileSync } from 'node:fs';
import { join, relative } from 'node:path';
import { fileURLToPath } from 'node:url';
import { decode, encode } from 'fast-png';
import { glyphWidth, glyphHeight, textPixels } from './bitmap-font.ts';

const root = fileURLToPath(new URL('../..', import.meta.url));
const cli = join(root, 'src/cli/main.ts');

function option(name: string, fallback?: string): string {
  const at = process.argv.indexOf(`--${name}`);
  const value = at >= 0 ? process.argv[at + 1] : fallback;
  if (value === undefined) throw new Error(`contact-sheet: --${name} is required`);
  return value;
}

interface Row {
  name: string;
  path: string;
}

/** The model file of a row: the path itself, or the .glb/.gltf under it (a "Required" variant first). */
function modelFile(dir: string): string | undefined {
  if (statSync(dir).isFile()) return /\.(glb|gltf)$/i.test(dir) ? dir : undefined;
  const found = (readdirSync(dir, { recursive: true }) as string[]).filter((f) => /\.(glb|gltf)$/i.test(f)).sort();
  const pick = found.find((f) => /required/i.test(f)) ?? found[0];
  return pick === undefined ? undefined : join(dir, pick);
}

interface Outcome {
  name: string;
  model: string;
  code: number;
  seconds: number;
  warnings: string[];
  notes: string[];
  error: string | undefined;
  invalidSamples: number;
  image: { width: number; height: number; data: Uint8Array } | undefined;
}

function render(row: Row, assets: string, env: string, out: string, size: number, spp: number): Outcome {
  const model = modelFile(join(assets, row.name, row.path));
  const outcome: Outcome = { name: row.name, model: model ?? join(assets, row.name, row.path), code: 1, seconds: 0, warnings: [], notes: [], error: undefined, invalidSamples: 0, image: undefined };
  if (model === undefined) {
    outcome.error = 'no .glb or .gltf found';
    return outcome;
  }
  const png = join(out, `${row.name}.png`);
  const started = performance.now();
  const result = spawnSync(process.execPath, [cli, 'render', model, '--width', String(size), '--height', String(size), '--spp', String(spp), '--env', env, '--out', png], { encoding: 'utf8', cwd: root });
  outcome.seconds = (performance.now() - started) / 1000;
  outcome.code = result.status ?? 1;
  const stderr = `${result.stderr ?? ''}`;
  writeFileSync(join(out, `${row.name}.log`), stderr);
  for (const line of stderr.split('\n')) {
    if (line.startsWith('warning: ')) outcome.warnings.push(line.slice(9));
    else if (line.startsWith('note: ')) outcome.notes.push(line.slice(6));
    else if (line.startsWith('error')) outcome.error = line;
    const invalid = /(\d+) invalid samples dropped/.exec(line);
    if (invalid) outcome.invalidSamples = Number(invalid[1]);
  }
  if (outcome.code === 0 && existsSync(png)) {
    const decoded = decode(readFileSync(png));
    outcome.image = { width: decoded.width, height: decoded.height, data: new Uint8Array(decoded.data.buffer, decoded.data.byteOffset, decoded.data.byteLength) };
  }
  return outcome;
}

/** Renders in a grid of `columns`, each cell the image over its label (white on dark grey). */
function sheet(outcomes: Outcome[], size: number, columns: number): { width: number; height: number; data: Uint8Array } {
  const scale = 2;
  const label = glyphHeight * scale + 6;
  const pad = 4;
  const cellW = size + pad;
  const cellH = size + label + pad;
  const rows = Math.ceil(outcomes.length / columns);
  const width = columns * cellW + pad;
  const height = rows * cellH + pad;
  const data = new Uint8Array(width * height * 4);
  for (let i = 0; i < width * height; i++) data.set([24, 24, 24, 255], i * 4);
  outcomes.forEach((o, k) => {
    const x0 = pad + (k % columns) * cellW;
    const y0 = pad + Math.floor(k / columns) * cellH;
    if (o.image) {
      for (let y = 0; y < Math.min(size, o.image.height); y++) {
        for (let x = 0; x < Math.min(size, o.image.width); x++) {
          const s = (y * o.image.width + x) * 4;
          data.set([o.image.data[s]!, o.image.data[s + 1]!, o.image.data[s + 2]!, 255], ((y0 + y) * width + x0 + x) * 4);
        }
      }
    } else {
      // A failed render: a red cell.
      for (let y = 0; y < size; y++) for (let x = 0; x < size; x++) data.set([120, 20, 20, 255], ((y0 + y) * width + x0 + x) * 4);
    }
    const flags = `${o.warnings.length > 0 ? ` W${o.warnings.length}` : ''}${o.invalidSamples > 0 ? ' INV' : ''}${o.error ? ' ERR' : ''}`;
    const text = `${o.name}${flags}`.slice(0, Math.floor(size / ((glyphWidth + 1) * scale)));
    for (const [gx, gy] of textPixels(text)) {
      for (let sy = 0; sy < scale; sy++) {
        for (let sx = 0; sx < scale; sx++) {
          const px = x0 + 2 + gx * scale + sx;
          const py = y0 + size + 3 + gy * scale + sy;
          if (px < width && py < height) data.set(o.warnings.length > 0 || o.error || o.invalidSamples > 0 ? [255, 200, 80, 255] : [235, 235, 235, 255], (py * width + px) * 4);
        }
      }
    }
  });
  return { width, height, data };
}

function report(outcomes: Outcome[], assets: string, spp: number, size: number): string {
  const lines = [`# Real-asset renders (${size}x${size}, ${spp} spp, studio HDRI)`, '', '| asset | result | s | invalid samples | warnings / notes |', '| --- | --- | --- | --- | --- |'];
  for (const o of outcomes) {
    const result = o.error ?? (o.code === 0 ? 'ok' : `exit ${o.code}`);
    const messages = [...o.warnings.map((w) => `warning: ${w}`), ...o.notes.map((n) => `note: ${n}`)].join('<br>').replace(/\|/g, '\\|');
    lines.push(`| ${o.name} (${relative(assets, o.model)}) | ${result.replace(/\|/g, '\\|')} | ${o.seconds.toFixed(1)} | ${o.invalidSamples} | ${messages} |`);
  }
  return `${lines.join('\n')}\n`;
}

const sources = option('sources');
const assets = option('assets');
const out = option('out');
const size = Number(option('size', '256'));
const spp = Number(option('spp', '32'));
const columns = Number(option('columns', '8'));
const only = process.argv.includes('--only') ? option('only').split(',') : undefined;
mkdirSync(out, { recursive: true });
const rows: Row[] = readFileSync(sources, 'utf8')
  .split('\n')
  .slice(1)
  .filter((line) => line.trim() !== '')
  .map((line) => {
    const [name, , path] = line.split('\t');
    return { name: name!, path: path! };
  });
const hdri = rows.pop()!;
const env = join(assets, hdri.name, hdri.path);
const outcomes: Outcome[] = [];
for (const row of rows) {
  if (only && !only.includes(row.name)) continue;
  const o = render(row, assets, env, out, size, spp);
  outcomes.push(o);
  console.log(`${o.name}: ${o.error ?? 'ok'} ${o.seconds.toFixed(1)}s${o.warnings.length ? `, ${o.warnings.length} warnings` : ''}${o.invalidSamples ? `, ${o.invalidSamples} invalid samples` : ''}`);
}
writeFileSync(join(out, 'report.md'), report(outcomes, assets, spp, size));
const image = sheet(outcomes, size, columns);
const sheetPath = process.argv.includes('--sheet') ? option('sheet') : join(out, 'contact-sheet.png');
writeFileSync(sheetPath, encode({ width: image.width, height: image.height, data: image.data, channels: 4 }));
console.log(`wrote ${sheetPath} and ${join(out, 'report.md')}`);
