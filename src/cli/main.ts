#!/usr/bin/env node
// The `gpu-renderer` executable (package.json "bin"); in the repository: node src/cli/main.ts render.
import { realpathSync } from 'node:fs';
import { pathToFileURL } from 'node:url';
import { isGpuRendererError } from '../errors/gpu-renderer-error.ts';
import { isSequence, parseCliArgs } from './args.ts';
import { formatSummary } from './render-format.ts';

/** Runs the CLI with `argv` (the arguments after the executable); resolves to the exit code. */
export async function main(argv: readonly string[]): Promise<number> {
  try {
    const command = parseCliArgs(argv);
    if (command.kind === 'help') {
      process.stdout.write(command.text);
      return 0;
    }
    // Loaded only for rendering, so --help and argument errors never touch WebGPU.
    if (command.kind === 'farm') {
      const { runFarmCommand } = await import('./farm-command.ts');
      return await runFarmCommand(command, { stdout: process.stdout, stderr: process.stderr });
    }
    if (isSequence(command)) {
      const { runSequenceCommand, formatSequenceSummary } = await import('./sequence-command.ts');
      process.stderr.write(`${formatSequenceSummary(await runSequenceCommand(command, { stderr: process.stderr }))}\n`);
      return 0;
    }
    const { runRenderCommand } = await import('./render-command.ts');
    const summary = await runRenderCommand(command, { stderr: process.stderr });
    process.stderr.write(`${formatSummary(summary)}\n`);
    return 0;
  } catch (error) {
    // GpuRendererError's message already starts with its field ("field: message").
    if (isGpuRendererError(error)) process.stderr.write(`error [${error.code}] ${error.message}\n`);
    else process.stderr.write(`error ${error instanceof Error ? (error.stack ?? error.message) : String(error)}\n`);
    return 1;
  }
}

function isEntryPoint(): boolean {
  const script = process.argv[1];
  if (script === undefined) return false;
  try {
    // Through npm's bin symlink argv[1] is the link; the module URL is the resolved file.
    return import.meta.url === pathToFileURL(realpathSync(script)).href;
  } catch {
    return false;
  }
}

if (isEntryPoint()) {
  // Exit explicitly: a Dawn device can keep the event loop alive after the work is done.
  main(process.argv.slice(2)).then(
    (code) => process.exit(code),
    () => process.exit(1),
  );
}
