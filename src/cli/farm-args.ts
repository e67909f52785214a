/** `gpu-renderer farm submit | worker | status` arguments (no I/O; the farm itself is src/farm). */
import type { FarmCommand, FarmCommandBase, FarmStatusCommand, FarmSubmitCommand, FarmWorkerCommand, HelpCommand } from './commands.ts';
import { formatOptions, helpOption, optionSetters, parseOptions, type CliOption } from './option-table.ts';
import { integer, invalidOption, nonEmpty } from './option-values.ts';
import { parseRenderArgs } from './render-args.ts';
import { parseOrigin } from '../io/resource-policy.ts';
import { parsePathMapping } from '../farm/path-map.ts';

const text = nonEmpty('a value');
const milliseconds = integer(100, 86_400_000);
const submit = optionSetters<FarmSubmitCommand>();
const worker = optionSetters<FarmWorkerCommand>();
const status = optionSetters<FarmStatusCommand>();
const base = optionSetters<FarmCommandBase>();

/** Every subcommand's options. */
const commonOptions: readonly CliOption<FarmCommandBase>[] = [
  { flag: '--redis', value: '<url>', help: 'redis://host:port (default: REDIS_URL, else redis://127.0.0.1:6379)', apply: base.set('redis', text) },
  { flag: '--queue', value: '<name>', help: 'queue name (default gpu-renderer)', apply: base.set('queue', text) },
  helpOption,
];

interface FarmAction<C> {
  synopsis: string;
  /** What the subcommand does, wrapped as printed. */
  about: string;
  options: readonly CliOption<C>[];
}

const submitAction: FarmAction<FarmSubmitCommand> = {
  synopsis: 'gpu-renderer farm submit <model.glb | job.json> [render options]',
  about: `Enqueue a sequence: the render command's options (--frames, --fps, --animation,
--turntable, --variants, --cameras, --out with ####, --width, --spp, --env, ...), or a JSON
job file whose keys are those options in camelCase ("scene", "out", "frames", ...).`,
  options: [
    { flag: '--name', value: '<name>', help: "job name (default: the asset's name and a hash of the job)", apply: submit.set('name', text) },
    { flag: '--attempts', value: '<n>', help: 'tries per frame (default 3)', apply: submit.set('attempts', integer(1, 100)) },
    { flag: '--backoff-ms', value: '<ms>', help: 'first retry delay, doubling per retry (default 5000)', apply: submit.set('backoffMs', integer(0, 86_400_000)) },
  ],
};

const workerAction: FarmAction<FarmWorkerCommand> = {
  synopsis: 'gpu-renderer farm worker',
  about: `Render frames until stopped (SIGINT / SIGTERM finish the frame in hand). A job is untrusted:
its scene, environment map and output must resolve (after --path-map and symbolic links) inside
the roots, or the frame is refused (FARM_JOB_REFUSED, shown by farm status); nothing is written
outside them.`,
  options: [
    { flag: '--exit-when-idle', help: 'exit once nothing is waiting, delayed or active', apply: worker.assign('exitWhenIdle', true) },
    { flag: '--lock-duration', value: '<ms>', help: "a dead worker's frame is taken over after this (default 30000)", apply: worker.set('lockDuration', milliseconds) },
    { flag: '--stalled-interval', value: '<ms>', help: 'how often to look for such frames (default 15000)', apply: worker.set('stalledInterval', milliseconds) },
    { flag: '--output-root', value: '<dir>', help: 'frames may be written only inside this folder (repeatable; required, or GPU_RENDERER_FARM_OUTPUT_ROOTS)', apply: (command, value = '', flag) => void (command.outputRoots ??= []).push(text(value, flag)) },
    { flag: '--asset-root', value: '<dir>', help: "scenes, environment maps and every file they reference are read only inside this folder (repeatable; required, or GPU_RENDERER_FARM_ASSET_ROOTS)", apply: (command, value = '', flag) => void (command.assetRoots ??= []).push(text(value, flag)) },
    { flag: '--path-map', value: '<from=to>', help: "read a job's paths under FROM as the same paths under TO, the longest FROM first (repeatable, or GPU_RENDERER_FARM_PATH_MAP)", apply: (command, value = '', flag) => void (command.pathMap ??= []).push(parsePathMapping(value, flag)) },
    { flag: '--allow-origin', value: '<origin>', help: "let assets' references fetch from this origin (repeatable, comma separated, or GPU_RENDERER_FARM_ALLOW_ORIGINS); jobs cannot add origins", apply: (command, value = '', flag) => void (command.allowedOrigins ??= []).push(...value.split(',').map((origin) => parseOrigin(origin.trim(), flag))) },
  ],
};

const statusAction: FarmAction<FarmStatusCommand> = {
  synopsis: 'gpu-renderer farm status [job]',
  about: "Progress of every job (or one), and the queue's counts.",
  options: [
    { flag: '--json', help: 'machine-readable', apply: status.assign('json', true) },
    { flag: '--wait', help: 'poll until every job listed is complete or failed', apply: status.assign('wait', true) },
    { flag: '--timeout', value: '<seconds>', help: 'with --wait: give up after this long (exit code 2)', apply: status.set('timeoutSeconds', integer(1, 31_536_000)) },
  ],
};

/** The options of each subcommand, as the help lists them (the common ones last); docs/cli.md lists the same. */
export const farmOptionSections = {
  submit: submitAction.options,
  worker: workerAction.options,
  status: statusAction.options,
  common: commonOptions,
} as const;

const indent = (paragraph: string): string => paragraph.split('\n').map((line) => `      ${line}\n`).join('');

export const farmUsage = `Usage: gpu-renderer farm <submit | worker | status> [options]

A render farm on BullMQ and Redis: a sequence becomes one queue job per frame; workers on any
number of machines (each with its own GPU, all seeing the same paths) render frames and write them
to the shared output directory atomically; a frame is retried with backoff, taken over by another
worker when its worker dies (after the lock duration), and written once.

${[submitAction, workerAction, statusAction].map((action) => `  ${action.synopsis}\n${indent(action.about)}${formatOptions(action.options as readonly CliOption<never>[], 6)}`).join('')}
Every subcommand:
${formatOptions(commonOptions)}`;

/** Parses `action`'s own and common options out of `argv`; the other arguments are left in `rest`. */
function parseAction<C extends FarmCommand>(argv: readonly string[], action: FarmAction<C>, command: C): string[] | 'help' {
  const parsed = parseOptions(argv, [...action.options, ...(commonOptions as readonly CliOption<C>[])], command, 'keep');
  return parsed.kind === 'help' ? 'help' : parsed.rest;
}

const flagOf = (arg: string): string => arg.split('=')[0]!;

export function parseFarmArgs(argv: readonly string[]): FarmCommand | HelpCommand {
  const help = { kind: 'help', text: farmUsage } as const;
  const [action, ...args] = argv;
  if (action === undefined || action === '-h' || action === '--help' || action === 'help') return help;
  if (action === 'worker') {
    const command: FarmWorkerCommand = { kind: 'farm', action, exitWhenIdle: false };
    const rest = parseAction(args, workerAction, command);
    if (rest === 'help') return help;
    if (rest.length > 0) invalidOption(rest[0]!.startsWith('-') ? flagOf(rest[0]!) : 'command', `unknown farm worker argument ${JSON.stringify(rest[0])} (see farm --help)`);
    return command;
  }
  if (action === 'status') {
    const command: FarmStatusCommand = { kind: 'farm', action, json: false, wait: false };
    const rest = parseAction(args, statusAction, command);
    if (rest === 'help') return help;
    const unknown = rest.find((a) => a.startsWith('-'));
    if (unknown !== undefined) invalidOption(flagOf(unknown), 'unknown farm status option (see farm --help)');
    if (rest.length > 1) invalidOption('job', 'name at most one job');
    if (rest[0] !== undefined) command.job = rest[0];
    if (command.timeoutSeconds !== undefined && !command.wait) invalidOption('--timeout', 'applies with --wait');
    return command;
  }
  if (action !== 'submit') invalidOption('command', `unknown farm command ${JSON.stringify(action)} (expected submit, worker or status)`);
  const command: FarmSubmitCommand = { kind: 'farm', action };
  const rest = parseAction(args, submitAction, command);
  if (rest === 'help') return help;
  const positional = rest.filter((a) => !a.startsWith('-'));
  if (positional.length === 1 && /\.json$/i.test(positional[0]!)) {
    if (rest.length > 1) invalidOption(flagOf(rest.find((a) => a !== positional[0])!), 'with a job file, give the render options in the file');
    return { ...command, jobFile: positional[0]! };
  }
  const render = parseRenderArgs(rest);
  if (render.kind === 'help') return help;
  return { ...command, render };
}
