// The option-table engine (src/cli/option-table.ts) on a table of its own: what a row means to the
// parser (values, switches, optional values, unknown options kept or refused) and to the help.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { formatOptions, helpOption, optionSetters, parseOptions, type CliOption } from '../../src/cli/option-table.ts';
import { integer, oneOf } from '../../src/cli/option-values.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';

interface Toy {
  size: number;
  loud: boolean;
  mode?: true | 'a' | 'b';
}

const { set, assign } = optionSetters<Toy>();
const mode = oneOf('a', 'b');
const table: readonly CliOption<Toy>[] = [
  { flag: '--size', value: '<n>', help: 'the size, an integer in 1..9', apply: set('size', integer(1, 9)) },
  { flag: '--loud', help: 'a switch', apply: assign('loud', true) },
  { flag: '--mode', value: '[a|b]', optional: ['a', 'b'], help: 'an optional value', apply: (toy, value, flag) => void (toy.mode = value === undefined ? true : mode(value, flag)) },
  helpOption,
];

function parse(argv: string[], unknown: 'error' | 'keep' = 'error'): { toy: Toy; rest: string[]; given: string[] } {
  const toy: Toy = { size: 1, loud: false };
  const parsed = parseOptions(argv, table, toy, unknown);
  assert.equal(parsed.kind, 'parsed');
  return { toy, rest: parsed.kind === 'parsed' ? parsed.rest : [], given: parsed.kind === 'parsed' ? [...parsed.given] : [] };
}

function refuses(argv: string[], field: string, message: RegExp): void {
  assert.throws(() => parse(argv), (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_OPTION' && e.field === field && message.test(e.message));
}

test('values in both forms, switches, positionals in order, `--` ends the options', () => {
  assert.deepEqual(parse(['x', '--size', '3', 'y', '--loud']), { toy: { size: 3, loud: true }, rest: ['x', 'y'], given: ['--size', '--loud'] });
  assert.deepEqual(parse(['--size=4', '--', '--loud']), { toy: { size: 4, loud: false }, rest: ['--loud'], given: ['--size'] });
  // A value may start with one dash (negative numbers), in either form.
  refuses(['--size', '-2'], '--size', /expected an integer, got "-2"/);
  refuses(['--size=-2'], '--size', /expected an integer, got "-2"/);
});

test('an optional value is taken only from the words it may be', () => {
  assert.deepEqual(parse(['--mode']).toy.mode, true);
  assert.deepEqual(parse(['--mode', 'b', 'scene']), { toy: { size: 1, loud: false, mode: 'b' }, rest: ['scene'], given: ['--mode'] });
  assert.deepEqual(parse(['--mode', 'scene']), { toy: { size: 1, loud: false, mode: true }, rest: ['scene'], given: ['--mode'] });
  refuses(['--mode=c'], '--mode', /expected a or b/);
});

test('typed errors name the flag', () => {
  refuses(['--size'], '--size', /expects a value/);
  refuses(['--size', '--loud'], '--size', /expects a value/);
  refuses(['--loud=yes'], '--loud', /takes no value/);
  refuses(['--sise=3'], '--sise', /unknown option/);
  refuses(['-z'], '-z', /unknown option/);
});

test('help is answered before the options after it; with keep, unknown options stay for the next parser', () => {
  assert.deepEqual(parseOptions(['--size', '2', '-h', '--bogus'], table, { size: 1, loud: false }), { kind: 'help' });
  assert.deepEqual(parse(['a.glb', '--spp', '16', '--size', '2', '--out=x.png', '--', '-b'], 'keep').rest, ['a.glb', '--spp', '16', '--out=x.png', '--', '-b']);
});

test('the help lists every row once, wrapped beside the flags', () => {
  const help = formatOptions(table, 2, 40);
  const lines = help.trimEnd().split('\n');
  assert.ok(lines.every((line) => line.length <= 40), help);
  assert.deepEqual(lines.filter((line) => /^ {2}-/.test(line)).map((line) => line.slice(2, 26).trim()), ['--size <n>', '--loud', '--mode [a|b]', '-h, --help']);
  // Continuation lines start at the help column.
  assert.ok(lines.filter((line) => !/^ {2}-/.test(line)).every((line) => /^ {27}\S/.test(line)), help);
  assert.match(formatOptions(table), /^ {2}--size <n> {15}the size, an integer in 1\.\.9\n/);
});
