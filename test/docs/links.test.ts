// The documentation's links: every relative link in README.md, docs/*.md, demo/README.md and
// bench/README.md, and every absolute link into the project's own repository, names a file or
// folder of the repository, and every #anchor a heading of the page it points to (with GitHub's
// heading ids). And the README's browser quick start is the text of
// test/bundle/quick-start, which test/bundle/vite-quick-start.test.ts runs in Chromium.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { existsSync, readdirSync, readFileSync, statSync } from 'node:fs';
import { dirname, join, relative, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { isAbsoluteLink, linkTargets, repositoryPath } from '../../scripts/markdown-links.ts';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const pkg = JSON.parse(readFileSync(join(root, 'package.json'), 'utf8')) as { homepage: string };
// The repository's own address (package.json's homepage without its #readme): links to files the
// npm package does not ship (sources, tests) are absolute links there, checked here like relative ones.
const repository = pkg.homepage.replace(/#.*$/, '');
const pages = [
  'README.md',
  'bench/README.md',
  'demo/README.md',
  ...readdirSync(join(root, 'docs')).filter((f) => f.endsWith('.md')).map((f) => `docs/${f}`),
];

/** GitHub's ids of a page's headings: lower case, punctuation dropped, spaces to hyphens, repeats numbered. */
function headingIds(markdown: string): Set<string> {
  const ids = new Set<string>();
  const seen = new Map<string, number>();
  const withoutFences = markdown.replace(/^(```|~~~)[^\n]*\n[\s\S]*?^\1[^\n]*$/gm, '');
  for (const m of withoutFences.matchAll(/^#{1,6}\s+(.+?)\s*#*\s*$/gm)) {
    const text = m[1]!.replace(/\[([^\]]*)\]\([^)]*\)/g, '$1');
    const base = text.toLowerCase().replace(/[^\p{L}\p{M}\p{N}\p{Pc}\- ]/gu, '').replace(/ /g, '-');
    const n = seen.get(base) ?? 0;
    seen.set(base, n + 1);
    ids.add(n === 0 ? base : `${base}-${n}`);
  }
  return ids;
}

test('every relative link in the README, docs/, demo/ and bench/README.md, and every link into the repository, resolves', () => {
  const broken: string[] = [];
  let checked = 0;
  for (const page of pages) {
    const file = join(root, page);
    const markdown = readFileSync(file, 'utf8');
    for (const target of linkTargets(markdown)) {
      const inRepository = repositoryPath(target, repository);
      if (isAbsoluteLink(target) && inRepository === undefined) continue; // other sites, mailto:, data:
      checked++;
      const [path = '', anchor] = target.split('#', 2) as [string, string | undefined];
      const resolved = inRepository !== undefined ? join(root, inRepository) : path === '' ? file : resolve(dirname(file), decodeURIComponent(path));
      if (!resolved.startsWith(root) || !existsSync(resolved)) {
        broken.push(`${page}: ${target} (no ${relative(root, resolved) || resolved})`);
        continue;
      }
      if (anchor !== undefined && statSync(resolved).isFile() && resolved.endsWith('.md')) {
        if (!headingIds(readFileSync(resolved, 'utf8')).has(anchor)) broken.push(`${page}: ${target} (no heading #${anchor})`);
      }
    }
  }
  assert.ok(checked > 100, `only ${checked} links found: is the link pattern right?`);
  assert.deepEqual(broken, []);
});

test("the README's browser quick start is test/bundle/quick-start, which a test runs", () => {
  const readme = readFileSync(join(root, 'README.md'), 'utf8');
  for (const name of ['index.html', 'main.js']) {
    // The fenced block right after the file's name, e.g. "`main.js`:".
    const m = readme.match(new RegExp('^`' + name.replace('.', '\\.') + '`:\\n\\n```[a-z]*\\n([\\s\\S]*?)^```$', 'm'));
    assert.ok(m, `README.md has no \`${name}\`: block`);
    assert.equal(m[1], readFileSync(join(root, 'test/bundle/quick-start', name), 'utf8'), `README.md's ${name} differs from test/bundle/quick-start/${name}`);
  }
});
