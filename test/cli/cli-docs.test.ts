// docs/cli.md lists the options the CLI has: the option lists of its `gpu-renderer ... --help`
// blocks (read from the Markdown) name the same flags, with the same value placeholders, as the
// option tables the parser and the help are made from.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { farmOptionSections } from '../../src/cli/farm-args.ts';
import type { CliOption } from '../../src/cli/option-table.ts';
import { renderOptions } from '../../src/cli/render-options.ts';

const doc = readFileSync(new URL('../../docs/cli.md', import.meta.url), 'utf8');

/** The fenced blocks of the Markdown whose first line is `Usage: <command>`. */
function usageBlocks(command: string): string[] {
  const blocks = [...doc.matchAll(/^```text\n([\s\S]*?)^```$/gm)].map((m) => m[1]!);
  return blocks.filter((block) => block.startsWith(`Usage: ${command} `));
}

/**
 * An option list's rows as `-h, --flag <value>`: a line indented by at most six spaces (help text
 * continues at column 27) that starts with a flag and its placeholder, if any, then a space.
 */
function listedOptions(block: string): string[] {
  return block.split('\n').flatMap((line) => /^ {2,6}((?:-\w, )?--[a-z][a-z-]*(?: [<[]\S*[>\]])?)(?: |$)/.exec(line)?.[1] ?? []);
}

function rows(options: readonly CliOption<never>[]): string[] {
  return options.map((o) => `${o.short !== undefined ? `-${o.short}, ` : ''}${o.flag}${o.value !== undefined ? ` ${o.value}` : ''}`);
}

test('docs/cli.md lists every render option, and only those', () => {
  const [block, ...more] = usageBlocks('gpu-renderer render');
  assert.ok(block !== undefined && more.length === 0, 'docs/cli.md has one `gpu-renderer render --help` block');
  assert.deepEqual(listedOptions(block).sort(), rows(renderOptions).sort());
});

test('docs/cli.md lists every farm option, and only those', () => {
  const [block, ...more] = usageBlocks('gpu-renderer farm');
  assert.ok(block !== undefined && more.length === 0, 'docs/cli.md has one `gpu-renderer farm --help` block');
  const tables = [farmOptionSections.submit, farmOptionSections.worker, farmOptionSections.status, farmOptionSections.common] as readonly (readonly CliOption<never>[])[];
  assert.deepEqual(listedOptions(block).sort(), tables.flatMap(rows).sort());
});

test('the option-list reader finds rows and skips the help text beside them', () => {
  const block = [
    'Usage: x', '', 'Options:',
    '  --width <px>             image width, or',
    '                           --not-a-row (a continuation)',
    '      --prose, --in a paragraph',
    '  --camera-position <x,y,z> a long row',
    '  --half                   a switch',
    '  -h, --help               show this help',
  ].join('\n');
  assert.deepEqual(listedOptions(block), ['--width <px>', '--camera-position <x,y,z>', '--half', '-h, --help']);
});
