#!/usr/bin/env node
// The `gpu-renderer` executable (package.json "bin"); in the repository: node src/cli/main.ts render.
import { spawn } from 'node:child_process';
import { realpathSync } from 'node:fs';
import { pathToFileURL } from 'node:url';
import { isGpuRendererError } from '../errors/gpu-renderer-error.ts';
import { isSequence, parseCliArgs } from './args.ts';
import { createDawnNoticeFilter } from './dawn-notices.ts';
import type { ProgressStream } from './progress.ts';
import { watchParent } from './parent-watch.ts';
import { formatSummary } from './render-format.ts';

/** Set in the rendering child process; its value is the parent's terminal width ('' when stderr is no terminal). */
const CHILD_ENV = 'GPU_RENDERER_CLI_STDERR_COLUMNS';

/** Runs the CLI with `argv` (the arguments after the executable); resolves to the exit code. */
export async function main(argv: readonly string[], stderr: ProgressStream = process.stderr): Promise<number> {
  try {
    const command = parseCliArgs(argv);
    if (command.kind === 'help') {
      process.stdout.write(command.text);
      return 0;
    }
    // Loaded only for rendering, so --help and argument errors never touch WebGPU.
    if (command.kind === 'farm') {
      const { runFarmCommand } = await import('./farm-command.ts');
      return await runFarmCommand(command, { stdout: process.stdout, stderr });
    }
    if (isSequence(command)) {
      const { runSequenceCommand, formatSequenceSummary } = await import('./sequence-command.ts');
      stderr.write(`${formatSequenceSummary(await runSequenceCommand(command, { stderr }))}\n`);
      return 0;
    }
    const { runRenderCommand } = await import('./render-command.ts');
    const summary = await runRenderCommand(command, { stderr });
    stderr.write(`${formatSummary(summary)}\n`);
    return 0;
  } catch (error) {
    // GpuRendererError's message already starts with its field ("field: message").
    if (isGpuRendererError(error)) stderr.write(`error [${error.code}] ${error.message}\n`);
    else stderr.write(`error ${error instanceof Error ? (error.stack ?? error.message) : String(error)}\n`);
    return 1;
  }
}

/**
 * Renders in a child process whose stderr passes through the Dawn notice filter (dawn-notices.ts);
 * stdin and stdout are the parent's, and an IPC channel tells the child when this process dies
 * (parent-watch.ts). Resolves to the child's exit code (128 + n for a signal).
 */
function renderInChild(argv: readonly string[]): Promise<number> {
  const script = process.argv[1]!;
  const columns = process.stderr.isTTY ? String(process.stderr.columns ?? 80) : '';
  const child = spawn(process.execPath, [...process.execArgv, script, ...argv], { stdio: ['inherit', 'inherit', 'pipe', 'ipc'], env: { ...process.env, [CHILD_ENV]: columns } });
  const filter = createDawnNoticeFilter((text) => process.stderr.write(text));
  child.stderr!.setEncoding('utf8').on('data', (text: string) => filter.push(text));
  // Ctrl-C reaches the whole process group: the child decides how to end; the parent waits for it.
  const forward = (signal: NodeJS.Signals) => (): void => void child.kill(signal);
  const handlers = (['SIGINT', 'SIGTERM', 'SIGHUP'] as const).map((signal) => [signal, forward(signal)] as const);
  for (const [signal, handler] of handlers) process.on(signal, handler);
  return new Promise((resolve) => {
    child.on('error', (error) => {
      process.stderr.write(`error cannot start the renderer process: ${error.message}\n`);
      resolve(1);
    });
    child.on('close', (code, signal) => {
      filter.end();
      for (const [name, handler] of handlers) process.off(name, handler);
      resolve(code ?? 128 + (signal === 'SIGINT' ? 2 : signal === 'SIGTERM' ? 15 : 1));
    });
  });
}

/** The stderr the rendering child writes to: the parent's terminal width and TTY-ness, not the pipe's. */
function childStderr(columns: string): ProgressStream {
  return { write: (text: string) => process.stderr.write(text), isTTY: columns !== '', ...(columns !== '' ? { columns: Number(columns) } : {}) };
}

/** Whether `argv` renders: a still, a sequence or a farm worker (anything else, help and argument errors, runs in this process). */
function renders(argv: readonly string[]): boolean {
  try {
    const command = parseCliArgs(argv);
    return command.kind === 'render' || (command.kind === 'farm' && command.action === 'worker');
  } catch {
    return false;
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
  const argv = process.argv.slice(2);
  const columns = process.env[CHILD_ENV];
  // The rendering child ends with its parent (nobody is left to read its output or wait for it).
  if (columns !== undefined) watchParent(() => process.exit(1));
  const run = columns !== undefined ? main(argv, childStderr(columns)) : renders(argv) ? renderInChild(argv) : main(argv);
  // Exit explicitly: a Dawn device can keep the event loop alive after the work is done.
  run.then(
    (code) => process.exit(code),
    () => process.exit(1),
  );
}
