/** `gpu-renderer farm submit | worker | status` arguments (no I/O; the farm itself is src/farm). */
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { parseRenderArgs, type RenderCommand } from './args.ts';

export const farmUsage = `Usage: gpu-renderer farm <submit | worker | status> [options]

A render farm on BullMQ and Redis: a sequence becomes one queue job per frame; workers on any
number of machines (each with its own GPU, all seeing the same paths) render frames and write them
to the shared output directory atomically; a frame is retried with backoff, taken over by another
worker when its worker dies (after the lock duration), and written once.

  gpu-renderer farm submit <model.glb | job.json> [render options]
      Enqueue a sequence: the render command's options (--frames, --fps, --animation,
      --turntable, --variants, --cameras, --out with ####, --width, --spp, --env, ...), or a JSON
      job file whose keys are those options in camelCase ("scene", "out", "frames", ...).
      --name <name>            job name (default: the asset's name and a hash of the job)
      --attempts <n>           tries per frame (default 3)
      --backoff-ms <ms>        first retry delay, doubling per retry (default 5000)
  gpu-renderer farm worker
      Render frames until stopped (SIGINT / SIGTERM finish the frame in hand).
      --exit-when-idle         exit once nothing is waiting, delayed or active
      --lock-duration <ms>     a dead worker's frame is taken over after this (default 30000)
      --stalled-interval <ms>  how often to look for such frames (default 15000)
  gpu-renderer farm status [job]
      Progress of every job (or one), and the queue's counts.
      --json                   machine-readable
      --wait                   poll until every job listed is complete or failed
      --timeout <seconds>      with --wait: give up after this long (exit code 2)

Every subcommand:
  --redis <url>            redis://host:port (default: REDIS_URL, else redis://127.0.0.1:6379)
  --queue <name>           queue name (default gpu-renderer)
`;

export interface FarmCommandBase {
  kind: 'farm';
  redis?: string;
  queue?: string;
}

export interface FarmSubmitCommand extends FarmCommandBase {
  action: 'submit';
  /** The render command (command line), or undefined with `jobFile`. */
  render?: RenderCommand;
  jobFile?: string;
  name?: string;
  attempts?: number;
  backoffMs?: number;
}

export interface FarmWorkerCommand extends FarmCommandBase {
  action: 'worker';
  exitWhenIdle: boolean;
  lockDuration?: number;
  stalledInterval?: number;
}

export interface FarmStatusCommand extends FarmCommandBase {
  action: 'status';
  job?: string;
  json: boolean;
  wait: boolean;
  timeoutSeconds?: number;
}

export type FarmCommand = FarmSubmitCommand | FarmWorkerCommand | FarmStatusCommand;

function invalid(field: string, message: string): never {
  throw new GpuRendererError('INVALID_OPTION', message, { field });
}

function integer(flag: string, text: string, min: number, max: number): number {
  if (!/^\d+$/.test(text)) invalid(flag, `expected an integer, got ${JSON.stringify(text)}`);
  const n = Number(text);
  if (n < min || n > max) invalid(flag, `must be between ${min} and ${max}, got ${n}`);
  return n;
}

/** Farm options of every subcommand and of each, taken out of argv; the rest (submit) goes to `render`'s parser. */
const farmFlags: Record<FarmCommand['action'], readonly string[]> = {
  submit: ['--redis', '--queue', '--name', '--attempts', '--backoff-ms'],
  worker: ['--redis', '--queue', '--exit-when-idle', '--lock-duration', '--stalled-interval'],
  status: ['--redis', '--queue', '--json', '--wait', '--timeout'],
};
const valueless = new Set(['--exit-when-idle', '--json', '--wait']);

export function parseFarmArgs(argv: readonly string[]): FarmCommand | { kind: 'help'; text: string } {
  const [action, ...rest] = argv;
  if (action === undefined || action === '-h' || action === '--help' || action === 'help') return { kind: 'help', text: farmUsage };
  if (action !== 'submit' && action !== 'worker' && action !== 'status') invalid('command', `unknown farm command ${JSON.stringify(action)} (expected submit, worker or status)`);
  const own: Record<string, string | true> = {};
  const remaining: string[] = [];
  for (let i = 0; i < rest.length; i++) {
    const arg = rest[i]!;
    if (arg === '-h' || arg === '--help') return { kind: 'help', text: farmUsage };
    const eq = arg.indexOf('=');
    const flag = eq >= 0 ? arg.slice(0, eq) : arg;
    if (!farmFlags[action].includes(flag)) {
      remaining.push(arg);
      continue;
    }
    if (valueless.has(flag)) {
      if (eq >= 0) invalid(flag, 'takes no value');
      own[flag] = true;
      continue;
    }
    const value = eq >= 0 ? arg.slice(eq + 1) : rest[++i];
    if (value === undefined || value === '' || (eq < 0 && value.startsWith('--'))) invalid(flag, 'expects a value');
    own[flag] = value;
  }
  const text = (flag: string): string | undefined => (typeof own[flag] === 'string' ? (own[flag] as string) : undefined);
  const base = { kind: 'farm' as const, ...(text('--redis') !== undefined ? { redis: text('--redis')! } : {}), ...(text('--queue') !== undefined ? { queue: text('--queue')! } : {}) };
  if (action === 'worker') {
    if (remaining.length > 0) invalid(remaining[0]!.startsWith('-') ? remaining[0]!.split('=')[0]! : 'command', `unknown farm worker argument ${JSON.stringify(remaining[0])} (see farm --help)`);
    return {
      ...base,
      action,
      exitWhenIdle: own['--exit-when-idle'] === true,
      ...(text('--lock-duration') !== undefined ? { lockDuration: integer('--lock-duration', text('--lock-duration')!, 100, 86_400_000) } : {}),
      ...(text('--stalled-interval') !== undefined ? { stalledInterval: integer('--stalled-interval', text('--stalled-interval')!, 100, 86_400_000) } : {}),
    };
  }
  if (action === 'status') {
    const positional = remaining.filter((a) => !a.startsWith('-'));
    const unknown = remaining.find((a) => a.startsWith('-'));
    if (unknown !== undefined) invalid(unknown.split('=')[0]!, 'unknown farm status option (see farm --help)');
    if (positional.length > 1) invalid('job', 'name at most one job');
    if (text('--timeout') !== undefined && own['--wait'] !== true) invalid('--timeout', 'applies with --wait');
    return {
      ...base,
      action,
      ...(positional[0] !== undefined ? { job: positional[0] } : {}),
      json: own['--json'] === true,
      wait: own['--wait'] === true,
      ...(text('--timeout') !== undefined ? { timeoutSeconds: integer('--timeout', text('--timeout')!, 1, 31_536_000) } : {}),
    };
  }
  const submit: FarmSubmitCommand = {
    ...base,
    action,
    ...(text('--name') !== undefined ? { name: text('--name')! } : {}),
    ...(text('--attempts') !== undefined ? { attempts: integer('--attempts', text('--attempts')!, 1, 100) } : {}),
    ...(text('--backoff-ms') !== undefined ? { backoffMs: integer('--backoff-ms', text('--backoff-ms')!, 0, 86_400_000) } : {}),
  };
  const positional = remaining.filter((a) => !a.startsWith('-'));
  if (positional.length === 1 && /\.json$/i.test(positional[0]!)) {
    if (remaining.length > 1) invalid(remaining.find((a) => a !== positional[0])!.split('=')[0]!, 'with a job file, give the render options in the file');
    return { ...submit, jobFile: positional[0]! };
  }
  const render = parseRenderArgs(remaining);
  if (render.kind === 'help') return { kind: 'help', text: farmUsage };
  return { ...submit, render };
}
