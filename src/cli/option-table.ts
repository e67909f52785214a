/**
 * Option tables: one row per command-line option (its flag, value, help text and what it sets),
 * from which both the parser and the help text are made, so a new option is one new row. The
 * arguments are split by `node:util` parseArgs (its tokens: `--flag value`, `--flag=value`, `-h`,
 * `--`); what the tokens mean is checked here, as typed errors naming the flag.
 */
import { parseArgs } from 'node:util';
import { invalidOption, type ValueParser } from './option-values.ts';

export interface CliOption<C> {
  /** The flag as typed, `--width`. */
  flag: `--${string}`;
  /** A one-letter alias (`h` for `-h`). */
  short?: string;
  /** The value's placeholder in the help (`<px>`); absent for a switch, which takes none. */
  value?: string;
  /**
   * The value may be left out (`--denoise [oidn|atrous]`): the words a following argument may be
   * to be taken as the value (anything else stays an argument of its own, e.g. the scene file).
   */
  optional?: readonly string[];
  /** What the option does, one paragraph (the help wraps it). */
  help: string;
  /** Records the option on the command being built: `value` is undefined for a switch or a left-out optional value. */
  apply(command: C, value: string | undefined, flag: string): void;
}

/** `-h, --help`, which every table lists and the parser answers before any other option. */
export const helpOption: CliOption<unknown> = { flag: '--help', short: 'h', help: 'show this help', apply: () => {} };

/** Row builders for a command type `C`: `set('width', integer(1, 16384))` stores the parsed value. */
export function optionSetters<C>() {
  return {
    /** Stores the parsed value in `key`. */
    set<K extends keyof C>(key: K, parse: ValueParser<C[K]>): CliOption<C>['apply'] {
      return (command, value, flag) => void (command[key] = parse(value ?? '', flag));
    },
    /** A switch: stores `constant` in `key`. */
    assign<K extends keyof C>(key: K, constant: C[K]): CliOption<C>['apply'] {
      return (command) => void (command[key] = constant);
    },
  };
}

export type ParsedOptions = { kind: 'help' } | {
  kind: 'parsed';
  /** The arguments that are not the table's options, in order (with `keep`, unknown options too, and `--`). */
  rest: string[];
  /** The flags given. */
  given: ReadonlySet<string>;
};

function parseConfig(options: readonly CliOption<never>[]) {
  const config: Record<string, { type: 'string' | 'boolean'; short?: string }> = { help: { type: 'boolean', short: 'h' } };
  for (const option of options) {
    // An optional value is taken by hand (parseArgs' string options always take the next argument).
    const type = option.value !== undefined && option.optional === undefined ? 'string' : 'boolean';
    config[option.flag.slice(2)] = { type, ...(option.short !== undefined ? { short: option.short } : {}) };
  }
  return config;
}

/**
 * Applies the options of `argv` found in `options` to `command`, in order. Unknown options are
 * INVALID_OPTION errors, or with `keep` are left in `rest` with everything else (for a second
 * parser: `farm submit` passes the render options on). A value is refused when missing or when it
 * is the next flag (`--width --height 3`); `--flag=-1` and `--flag -1` both pass -1.
 */
export function parseOptions<C>(argv: readonly string[], options: readonly CliOption<C>[], command: C, unknown: 'error' | 'keep' = 'error'): ParsedOptions {
  const byName = new Map(options.map((option) => [option.flag.slice(2), option]));
  const { tokens } = parseArgs({ args: [...argv], options: parseConfig(options), strict: false, allowPositionals: true, tokens: true });
  const consumed = new Set<number>();
  const given = new Set<string>();
  for (let t = 0; t < tokens.length; t++) {
    const token = tokens[t]!;
    if (token.kind === 'option-terminator') {
      if (unknown === 'error') consumed.add(token.index);
      break;
    }
    if (token.kind !== 'option') continue;
    if (token.name === 'help') return { kind: 'help' };
    const option = byName.get(token.name);
    if (option === undefined) {
      if (unknown === 'error') invalidOption(argv[token.index]!.split('=')[0]!, 'unknown option (see --help)');
      continue;
    }
    const flag = option.flag;
    let value = token.value;
    consumed.add(token.index);
    if (option.optional !== undefined) {
      const next = tokens[t + 1];
      if (value === undefined && next?.kind === 'positional' && next.index === token.index + 1 && option.optional.includes(next.value)) {
        value = next.value;
        consumed.add(next.index);
        t++;
      }
    } else if (option.value === undefined) {
      if (value !== undefined) invalidOption(flag, 'takes no value');
    } else {
      if (value === undefined || (!token.inlineValue && value.startsWith('--') && value.length > 2)) invalidOption(flag, 'expects a value');
      if (!token.inlineValue) consumed.add(token.index + 1);
    }
    given.add(flag);
    option.apply(command, value, flag);
  }
  return { kind: 'parsed', rest: argv.filter((_, i) => !consumed.has(i)), given };
}

/** A table's help: one option a row, the help text wrapped at `width` columns beside the flags. */
export function formatOptions(options: readonly CliOption<never>[], indent = 2, width = 100): string {
  const column = indent + 25;
  return options.map((option) => {
    const flags = `${option.short !== undefined ? `-${option.short}, ` : ''}${option.flag}${option.value !== undefined ? ` ${option.value}` : ''}`;
    const lines: string[] = [];
    let line = `${' '.repeat(indent)}${flags}`.padEnd(column - 1);
    for (const [i, word] of option.help.split(/\s+/).entries()) {
      if (i > 0 && line.length + 1 + word.length > width) {
        lines.push(line);
        line = ' '.repeat(column - 1);
      }
      line += ` ${word}`;
    }
    lines.push(line);
    return `${lines.join('\n')}\n`;
  }).join('');
}
