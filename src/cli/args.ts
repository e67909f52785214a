/** Command-line parsing for `gpu-renderer`, kept free of I/O so it is testable in isolation. */
import type { CliCommand } from './commands.ts';
import { parseFarmArgs } from './farm-args.ts';
import { invalidOption } from './option-values.ts';
import { parseRenderArgs, usage } from './render-args.ts';

export type { CliCommand, HelpCommand, RenderCommand } from './commands.ts';
export { renderDefaults } from './render-options.ts';
export { isGltfPath, isSequence, parseRenderArgs, usage } from './render-args.ts';

/** Parses the whole argument list after the executable (`['render', ...]`). */
export function parseCliArgs(argv: readonly string[]): CliCommand {
  const [sub, ...rest] = argv;
  if (sub === undefined || sub === '-h' || sub === '--help' || sub === 'help') return { kind: 'help', text: usage };
  if (sub === 'farm') return parseFarmArgs(rest);
  if (sub !== 'render') invalidOption('command', `unknown command ${JSON.stringify(sub)} (expected "render" or "farm")`);
  return parseRenderArgs(rest);
}
