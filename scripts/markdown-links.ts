// The links of the Markdown pages, as the documentation checks read them: test/docs/links.test.ts
// (every link resolves in the repository) and scripts/pack-check.ts (every relative link of a
// packed page resolves in the tarball, so the pages read the same from node_modules and on the
// registry's page).
import { posix } from 'node:path';

/** The page without fenced code blocks and inline code spans, where brackets are not links. */
function prose(markdown: string): string {
  return markdown
    .replace(/^(```|~~~)[^\n]*\n[\s\S]*?^\1[^\n]*$/gm, '')
    .replace(/(`+)[\s\S]*?\1/g, '');
}

/** Link targets: inline links `[text](target)`, images `![alt](target)` and HTML `src`/`href`. */
export function linkTargets(markdown: string): string[] {
  const text = prose(markdown);
  const targets: string[] = [];
  for (const m of text.matchAll(/\]\(\s*<?([^)\s>]+)>?(?:\s+"[^"]*")?\s*\)/g)) targets.push(m[1]!);
  for (const m of text.matchAll(/\s(?:src|href)="([^"]+)"/g)) targets.push(m[1]!);
  return targets;
}

/** Whether a link target names a scheme (https:, mailto:, data:) rather than a relative path. */
export function isAbsoluteLink(target: string): boolean {
  return /^[a-z][a-z0-9+.-]*:/i.test(target);
}

/**
 * The repository path an absolute link into the project's own repository names
 * (`<repository>/blob/main/src/cli` -> `src/cli`; blob, tree and raw alike), else undefined.
 */
export function repositoryPath(target: string, repository: string): string | undefined {
  const prefix = `${repository.replace(/\/$/, '')}/`;
  if (!target.startsWith(prefix)) return undefined;
  const m = /^(?:blob|tree|raw)\/main\/([^#?]+)/.exec(target.slice(prefix.length));
  return m ? decodeURIComponent(m[1]!) : undefined;
}

/** The path a relative link of `page` names (both relative to the same root), or undefined for an absolute link or an anchor of the page itself. */
export function resolveLink(page: string, target: string): string | undefined {
  if (isAbsoluteLink(target) || target.startsWith('#')) return undefined;
  return posix.normalize(posix.join(posix.dirname(page), decodeURIComponent(target.split(/[#?]/, 1)[0]!))).replace(/\/$/, '');
}

/**
 * The relative links of the packed Markdown pages (`files`: the tarball's paths, `read`: a packed
 * file's text) that name no packed file or folder, as `page: target`. Anchors are not checked
 * here: the pages are the repository's, whose anchors test/docs/links.test.ts checks.
 */
export function unpackedLinks(files: ReadonlySet<string>, read: (path: string) => string): string[] {
  const folders = new Set([...files].flatMap((file) => file.split('/').slice(0, -1).map((_, i, parts) => parts.slice(0, i + 1).join('/'))));
  const broken: string[] = [];
  for (const page of [...files].filter((f) => f.endsWith('.md')).sort()) {
    for (const target of linkTargets(read(page))) {
      const path = resolveLink(page, target);
      if (path !== undefined && !files.has(path) && !folders.has(path)) broken.push(`${page}: ${target}`);
    }
  }
  return broken;
}

/** The packed pages and images no link reaches from `start` (README.md): shipped but unread. */
export function unlinkedFiles(files: ReadonlySet<string>, read: (path: string) => string, start: string, shipped: (file: string) => boolean): string[] {
  const reached = new Set([start]);
  const queue = [start];
  for (let page = queue.pop(); page !== undefined; page = queue.pop()) {
    if (!page.endsWith('.md')) continue;
    for (const target of linkTargets(read(page))) {
      const path = resolveLink(page, target);
      if (path !== undefined && files.has(path) && !reached.has(path)) {
        reached.add(path);
        queue.push(path);
      }
    }
  }
  return [...files].filter((file) => shipped(file) && !reached.has(file)).sort();
}
