// pack:check's link checks (scripts/markdown-links.ts) on a temporary package packed by npm itself
// (`npm pack --dry-run`): a README link to a page the package's "files" leave out, or to a source
// file, is reported; shipping the page and linking the source absolutely passes; a shipped page no
// link reaches is reported as unread.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { mkdirSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { linkTargets, repositoryPath, unlinkedFiles, unpackedLinks } from '../../scripts/markdown-links.ts';

function writeTree(dir: string, tree: Record<string, string>): void {
  for (const [path, text] of Object.entries(tree)) {
    mkdirSync(dirname(join(dir, path)), { recursive: true });
    writeFileSync(join(dir, path), text);
  }
}

/** The files `npm pack` puts in the tarball of the package in `dir`. */
function packedFiles(dir: string): Set<string> {
  const result = spawnSync('npm', ['pack', '--dry-run', '--json', '--ignore-scripts'], { cwd: dir, encoding: 'utf8', env: { ...process.env, npm_config_update_notifier: 'false' } });
  assert.equal(result.status, 0, result.stderr);
  return new Set((JSON.parse(result.stdout) as { files: { path: string }[] }[])[0]!.files.map((f) => f.path));
}

const pages = {
  'docs/guide.md': '# Guide\n\nBack to the [README](../README.md); the [sources](../src/index.js).\n',
  'docs/extra.md': '# Extra\n',
  'src/index.js': 'export {};\n',
};

test('pack:check reports README and docs links to files the tarball does not hold', () => {
  const dir = mkdtempSync(join(tmpdir(), 'gpu-renderer-packed-links-'));
  try {
    const readme = '# Toy\n\n<img src="docs/logo.png">\n\nSee the [guide](docs/guide.md#guide) and [the code](src/index.js); `[not a link](nowhere.md)`.\n';
    writeTree(dir, { ...pages, 'README.md': readme, 'docs/logo.png': 'png', 'package.json': JSON.stringify({ name: 'toy', version: '1.0.0', files: ['src/index.js'] }) });
    const read = (path: string): string => readFileSync(join(dir, path), 'utf8');
    // Without the docs in "files", every link into docs/ breaks (the README itself is always packed).
    assert.deepEqual(unpackedLinks(packedFiles(dir), read), ['README.md: docs/guide.md#guide', 'README.md: docs/logo.png']);

    // Shipping the pages the README links, and linking the sources absolutely, passes; the guide's
    // link to a source file is then the one left.
    writeTree(dir, { 'package.json': JSON.stringify({ name: 'toy', version: '1.0.0', files: ['docs/*.md', 'docs/logo.png'] }) });
    assert.deepEqual(unpackedLinks(packedFiles(dir), read), ['README.md: src/index.js', 'docs/guide.md: ../src/index.js']);
    writeTree(dir, {
      'README.md': readme.replace('(src/index.js)', '(https://github.com/example/toy/blob/main/src/index.js)'),
      'docs/guide.md': pages['docs/guide.md'].replace('../src/index.js', 'https://github.com/example/toy/blob/main/src/index.js'),
    });
    const files = packedFiles(dir);
    assert.deepEqual(unpackedLinks(files, read), []);
    // docs/extra.md is shipped, but no link from the README reaches it.
    assert.deepEqual(unlinkedFiles(files, read, 'README.md', (f) => f.startsWith('docs/')), ['docs/extra.md']);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});

test('link targets come from prose, not code; repository links name their path', () => {
  assert.deepEqual(linkTargets('[a](x.md) ![b](i.png "t") `[c](y.md)`\n```\n[d](z.md)\n```\n<a href="h.md">'), ['x.md', 'i.png', 'h.md']);
  const repo = 'https://github.com/example/toy';
  assert.equal(repositoryPath(`${repo}/blob/main/src/a%20b.ts#L3`, repo), 'src/a b.ts');
  assert.equal(repositoryPath(`${repo}/tree/main/test/bundle`, repo), 'test/bundle');
  assert.equal(repositoryPath('https://github.com/other/toy/blob/main/src/a.ts', repo), undefined);
});

test("this package's packed pages link only packed files, and the README reaches every packed page", () => {
  // The same checks as pack:check, without its build: what npm packs from the repository as it is.
  const root = fileURLToPath(new URL('../..', import.meta.url));
  const files = packedFiles(root);
  const read = (path: string): string => readFileSync(join(root, path), 'utf8');
  assert.ok(files.has('docs/cli.md') && files.has('demo/README.md'), 'the README links docs/ and demo/README.md: they are packed');
  assert.deepEqual(unpackedLinks(files, read), [], 'link these absolutely (the repository URL), or ship them in package.json "files"');
  assert.deepEqual(unlinkedFiles(files, read, 'README.md', (f) => /^(docs|demo)\//.test(f)), []);
});
