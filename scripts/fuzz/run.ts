/**
 * `npm run fuzz`: mutation fuzzing of every loader and of the renderer's options, in child
 * processes with time and memory limits, with escape detection (canary files outside each asset
 * folder, a local HTTP server no case may contact). Prints a summary table; writes a JSON report
 * and every failing case (regenerated from its seed) under --out. Exit status 1 on any untyped
 * error, hang, out-of-memory, crash, escape or prototype pollution, or a fault the renderer refuses
 * after a loader accepted it.
 *
 *   npm run fuzz                                    # the full run: 5000 glTF, 500 scene, 500 env, 500 option sets
 *   npm run fuzz -- --gltf 200 --env 50 --options 0 # a shorter run
 *   npm run fuzz -- --only gltf:1234                # one case again (its files go to --out)
 *
 * Options: --gltf N, --scene N, --env N, --options N, --seed S (default 1), --jobs J (default 2),
 * --timeout-ms T (default 30000; option sets get 6 x T), --memory-mb M (resident memory per child,
 * default 2048), --out DIR (default test-output/fuzz), --only KIND:INDEX, --quiet.
 */
import { fork, type ChildProcess } from 'node:child_process';
import { mkdirSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { createServer, type IncomingMessage, type Server, type ServerResponse } from 'node:http';
import type { AddressInfo } from 'node:net';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { buildCorpora, CASE_KINDS, makeCase, type CaseKind } from './cases.ts';
import type { LoaderCase } from './cases-gltf.ts';
import { isFailure, signature, summaryTable, type Outcome } from './outcome.ts';
import { touchedCanaries, type Servers, type WorkerSandbox } from './sandbox.ts';

export interface FuzzConfig {
  counts: Record<CaseKind, number>;
  seed: number;
  jobs: number;
  timeoutMs: number;
  memoryMb: number;
  out: string | undefined;
  only?: { kind: CaseKind; index: number };
  log: (line: string) => void;
}

export interface FuzzReport {
  outcomes: Outcome[];
  failures: Outcome[];
  /** Requests the denied server received that no case explains (counted as escapes too). */
  unattributedRequests: string[];
  table: string;
  seconds: number;
}

interface Request {
  server: 'denied' | 'allowed';
  url: string;
  tag: string | undefined;
}

const TAG = /c-(gltf|scene|env|options)-\d+/;

function startServers(requests: Request[]): Promise<{ servers: Servers; close: () => void }> {
  const open = new Set<ServerResponse>();
  const record = (server: Request['server']) => (req: IncomingMessage): void => void requests.push({ server, url: req.url ?? '', tag: TAG.exec(req.url ?? '')?.[0] });
  const denied = createServer((req, res) => {
    record('denied')(req);
    res.end(new Uint8Array(64).fill(0x42));
  });
  const allowed = createServer((req, res) => {
    record('allowed')(req);
    const url = req.url ?? '';
    if (url.endsWith('/slow')) {
      open.add(res); // never answered: the client's timeout must end it
      return;
    }
    if (url.endsWith('/huge')) {
      res.writeHead(200);
      const chunk = new Uint8Array(1 << 20);
      const pump = (): void => {
        while (res.write(chunk));
      };
      res.on('drain', pump);
      pump();
      open.add(res);
      return;
    }
    if (url.endsWith('/redirect')) {
      res.writeHead(302, { location: `${deniedOrigin}/${TAG.exec(url)?.[0] ?? 'untagged'}/redirected.bin` });
      res.end();
      return;
    }
    if (url.endsWith('/ok.bin')) return void res.end(new Uint8Array(4096));
    res.statusCode = 404;
    res.end();
  });
  let deniedOrigin = '';
  const listen = (server: Server): Promise<string> => new Promise((resolve) => server.listen(0, '127.0.0.1', () => resolve(`http://127.0.0.1:${(server.address() as AddressInfo).port}`)));
  return Promise.all([listen(denied), listen(allowed)]).then(([d, a]) => {
    deniedOrigin = d;
    return {
      servers: { denied: d, allowed: a },
      close: () => {
        for (const res of open) res.destroy();
        denied.closeAllConnections();
        allowed.closeAllConnections();
        denied.close();
        allowed.close();
      },
    };
  });
}

/** Resident memory of a process in MiB (Linux /proc), or 0 where unknown. */
function residentMb(pid: number | undefined): number {
  if (pid === undefined) return 0;
  try {
    const status = readFileSync(`/proc/${pid}/status`, 'utf8');
    const kb = Number(/VmRSS:\s+(\d+)/.exec(status)?.[1] ?? 0);
    return kb / 1024;
  } catch {
    return 0;
  }
}

interface Slot {
  id: number;
  child: ChildProcess | undefined;
  sandbox: Pick<WorkerSandbox, 'canaryFiles'>;
  busy: { kind: CaseKind; index: number; started: number; timer: NodeJS.Timeout; memory: NodeJS.Timeout; allowedOrigins: string[] } | undefined;
  stderr: string;
}

export async function runFuzz(config: FuzzConfig): Promise<FuzzReport> {
  const started = performance.now();
  const runDir = mkdtempSync(join(tmpdir(), 'gpu-renderer-fuzz-'));
  const requests: Request[] = [];
  const { servers, close } = await startServers(requests);
  const queue: Array<{ kind: CaseKind; index: number }> = [];
  if (config.only) queue.push(config.only);
  else for (const kind of CASE_KINDS) for (let index = 0; index < config.counts[kind]; index++) queue.push({ kind, index });
  const total = queue.length;
  const outcomes: Outcome[] = [];
  const workerScript = join(dirname(fileURLToPath(import.meta.url)), 'worker.ts');
  let lastLog = performance.now();

  const finished = new Promise<void>((resolveAll) => {
    const slots: Slot[] = [];
    const record = (outcome: Outcome): void => {
      outcomes.push(outcome);
      if (performance.now() - lastLog > 10_000) {
        lastLog = performance.now();
        config.log(`fuzz: ${outcomes.length}/${total} cases, ${outcomes.filter(isFailure).length} failing, ${((performance.now() - started) / 1000).toFixed(0)} s`);
      }
    };
    const checkEscapes = (slot: Slot, outcome: Outcome): Outcome => {
      const escapes: string[] = touchedCanaries(slot.sandbox as WorkerSandbox).map((f) => `read ${f}`);
      const tag = `c-${outcome.kind}-${outcome.index}`;
      for (const r of requests) {
        if (r.tag !== tag) continue;
        if (r.server === 'denied' || !(outcome.allowedOrigins ?? []).includes(servers.allowed)) escapes.push(`${r.server} server: GET ${r.url}`);
      }
      return escapes.length === 0 ? outcome : { ...outcome, status: 'escape', escapes };
    };
    let done = false;
    const finish = (): void => {
      if (done || slots.some((s) => s.busy !== undefined) || queue.length > 0) return;
      done = true;
      for (const s of slots) {
        const child = s.child;
        s.child = undefined;
        child?.removeAllListeners();
        child?.stderr?.destroy();
        child?.kill('SIGKILL');
      }
      resolveAll();
    };
    const next = (slot: Slot): void => {
      const job = queue.shift();
      if (job === undefined) return finish();
      const deadline = job.kind === 'options' ? 6 * config.timeoutMs : config.timeoutMs;
      const timer = setTimeout(() => fail(slot, 'hang', `no result within ${deadline} ms`), deadline);
      const memory = setInterval(() => {
        const mb = residentMb(slot.child?.pid);
        if (mb > config.memoryMb) fail(slot, 'oom', `resident memory ${mb.toFixed(0)} MiB over the ${config.memoryMb} MiB limit`);
      }, 100);
      slot.busy = { ...job, started: performance.now(), timer, memory, allowedOrigins: [] };
      slot.child!.send({ type: 'case', ...job });
    };
    const fail = (slot: Slot, status: 'hang' | 'oom' | 'crash', message: string): void => {
      const busy = slot.busy;
      slot.busy = undefined;
      if (busy) {
        clearTimeout(busy.timer);
        clearInterval(busy.memory);
        const oom = /heap out of memory|Allocation failed|OOM/i.test(slot.stderr);
        const outcome: Outcome = {
          kind: busy.kind,
          index: busy.index,
          status: status === 'crash' && oom ? 'oom' : status,
          ms: performance.now() - busy.started,
          notes: [],
          message: `${message}${slot.stderr ? `; stderr: ${slot.stderr.slice(-400)}` : ''}`,
          allowedOrigins: busy.allowedOrigins,
        };
        record(checkEscapes(slot, outcome));
      }
      const dying = slot.child;
      slot.child = undefined;
      dying?.removeAllListeners();
      dying?.kill('SIGKILL');
      spawn(slot);
    };
    const spawn = (slot: Slot): void => {
      if (done) return;
      slot.stderr = '';
      const child = fork(workerScript, [], {
        execArgv: [`--max-old-space-size=${Math.floor(config.memoryMb * 0.75)}`, '--disable-warning=ExperimentalWarning'],
        stdio: ['ignore', 'ignore', 'pipe', 'ipc'],
        serialization: 'advanced',
      });
      slot.child = child;
      child.stderr!.on('data', (d: Buffer) => {
        slot.stderr = (slot.stderr + d.toString()).slice(-4000);
      });
      child.on('message', (message: { type: string; outcome?: Outcome; message?: string; allowedOrigins?: string[] }) => {
        if (message.type === 'ready') return next(slot);
        if (message.type === 'started') {
          if (slot.busy) slot.busy.allowedOrigins = message.allowedOrigins ?? [];
          return;
        }
        if (message.type === 'fatal') return fail(slot, 'crash', message.message ?? 'worker failed');
        if (message.type !== 'result' || slot.busy === undefined) return;
        clearTimeout(slot.busy.timer);
        clearInterval(slot.busy.memory);
        slot.busy = undefined;
        record(checkEscapes(slot, message.outcome!));
        next(slot);
      });
      child.on('exit', (code, signal) => {
        if (slot.child !== child) return;
        fail(slot, 'crash', `worker exited (${code ?? signal})`);
      });
      child.send({ type: 'init', runDir, worker: slot.id, seed: config.seed, servers });
      slot.sandbox = { canaryFiles: ['secret.bin', 'secret.png', 'secret.hdr'].map((f) => join(runDir, `w${slot.id}`, 'canary', f)) };
    };
    const jobs = Math.max(1, Math.min(config.jobs, total));
    if (total === 0) return resolveAll();
    for (let id = 0; id < jobs; id++) {
      const slot: Slot = { id, child: undefined, sandbox: { canaryFiles: [] }, busy: undefined, stderr: '' };
      slots.push(slot);
      spawn(slot);
    }
  });
  await finished;
  close();
  const tagged = new Set(outcomes.map((o) => `c-${o.kind}-${o.index}`));
  const unattributedRequests = requests.filter((r) => r.server === 'denied' && (r.tag === undefined || !tagged.has(r.tag))).map((r) => r.url);
  outcomes.sort((a, b) => CASE_KINDS.indexOf(a.kind) - CASE_KINDS.indexOf(b.kind) || a.index - b.index);
  const failures = outcomes.filter(isFailure);
  const kinds = CASE_KINDS.filter((k) => config.counts[k] > 0 || config.only?.kind === k);
  const table = summaryTable(outcomes, kinds);
  if (config.out !== undefined) await writeReport(config, outcomes, failures, unattributedRequests, table, servers, runDir);
  rmSync(runDir, { recursive: true, force: true });
  return { outcomes, failures, unattributedRequests, table, seconds: (performance.now() - started) / 1000 };
}

/** The report, and each failing loader case's files (regenerated from its seed) for reproduction. */
async function writeReport(config: FuzzConfig, outcomes: Outcome[], failures: Outcome[], unattributed: string[], table: string, servers: Servers, runDir: string): Promise<void> {
  const out = config.out!;
  mkdirSync(out, { recursive: true });
  const groups = new Map<string, Outcome[]>();
  for (const o of outcomes.filter((x) => x.status !== 'ok' && x.status !== 'typed' && x.status !== 'aborted')) groups.set(signature(o), [...(groups.get(signature(o)) ?? []), o]);
  const distinct = [...groups.entries()].map(([sig, list]) => ({ signature: sig, count: list.length, examples: list.slice(0, 3) }));
  // Where the typed errors point (indices folded): what the mutants reached.
  const typedFields: Record<string, { count: number; example: string }> = {};
  for (const o of outcomes) {
    if (o.status !== 'typed') continue;
    // Errors about the whole document are told apart by their message's first words.
    const what = o.field ? o.field.replace(/\d+/g, 'i') : `'' ${(o.message ?? '').replace(/^in gltf\[\d+\] \([^)]*\): /, '').split(/[:(]/)[0]!.replace(/\d+/g, 'N').slice(0, 60)}`;
    const key = `${o.kind} ${o.code} ${what}`;
    typedFields[key] ??= { count: 0, example: `${o.message ?? ''} [${o.notes.join('; ')}]`.slice(0, 300) };
    typedFields[key].count++;
  }
  const typed = Object.fromEntries(Object.entries(typedFields).sort((a, b) => b[1].count - a[1].count));
  writeFileSync(join(out, 'report.json'), JSON.stringify({ seed: config.seed, counts: config.counts, table, failures, distinct, unattributedRequests: unattributed, typed }, null, 2));
  if (failures.length === 0) return;
  const corpora = await buildCorpora();
  for (const f of failures.slice(0, 50)) {
    if (f.kind === 'options') continue;
    const dir = join(out, 'cases', `c-${f.kind}-${f.index}`);
    mkdirSync(dir, { recursive: true });
    const c = makeCase(f.kind, f.index, config.seed, corpora, { canary: join(runDir, 'w0', 'canary'), asset: dir, servers, caseTag: `c-${f.kind}-${f.index}`, hasFifo: false }) as LoaderCase;
    for (const [name, bytes] of Object.entries(c.files)) {
      mkdirSync(dirname(join(dir, name)), { recursive: true });
      writeFileSync(join(dir, name), bytes);
    }
    writeFileSync(join(dir, 'case.json'), JSON.stringify({ outcome: f, notes: c.notes, source: c.source.kind === 'bytes' ? 'bytes' : c.source, options: c.options }, null, 2));
  }
}

function parseArgs(argv: readonly string[]): FuzzConfig {
  const config: FuzzConfig = { counts: { gltf: 5000, scene: 500, env: 500, options: 500 }, seed: 1, jobs: 2, timeoutMs: 30_000, memoryMb: 2048, out: 'test-output/fuzz', log: (l) => console.error(l) };
  for (let i = 0; i < argv.length; i++) {
    const flag = argv[i]!;
    const value = argv[i + 1];
    const int = (): number => {
      const n = Number(value);
      if (!Number.isInteger(n) || n < 0) throw new Error(`${flag} expects a non-negative integer, got ${value}`);
      i++;
      return n;
    };
    if (flag === '--gltf' || flag === '--scene' || flag === '--env' || flag === '--options') config.counts[flag.slice(2) as CaseKind] = int();
    else if (flag === '--seed') config.seed = int();
    else if (flag === '--jobs') config.jobs = Math.max(1, int());
    else if (flag === '--timeout-ms') config.timeoutMs = int();
    else if (flag === '--memory-mb') config.memoryMb = int();
    else if (flag === '--out') {
      config.out = value;
      i++;
    } else if (flag === '--only') {
      const [kind, index] = (value ?? '').split(':');
      if (!CASE_KINDS.includes(kind as CaseKind) || !Number.isInteger(Number(index))) throw new Error(`--only expects KIND:INDEX (kinds: ${CASE_KINDS.join(', ')})`);
      config.only = { kind: kind as CaseKind, index: Number(index) };
      i++;
    } else if (flag === '--quiet') config.log = () => {};
    else throw new Error(`unknown option ${flag}`);
  }
  return config;
}

if (process.argv[1] !== undefined && fileURLToPath(import.meta.url) === process.argv[1]) {
  const config = parseArgs(process.argv.slice(2));
  const report = await runFuzz(config);
  console.log(report.table);
  console.log(`${report.outcomes.length} cases in ${report.seconds.toFixed(0)} s (seed ${config.seed}, ${config.jobs} jobs); ${report.failures.length} failing${report.unattributedRequests.length ? `; ${report.unattributedRequests.length} unattributed requests to the denied server` : ''}`);
  for (const f of report.failures.slice(0, 20)) console.log(`  ${f.kind}:${f.index} ${f.status} ${f.code ?? f.errorName ?? ''} ${f.field ?? ''} ${f.message ?? ''} [${f.notes.join('; ')}]${f.escapes ? ` ${f.escapes.join(', ')}` : ''}`);
  if (config.out) console.log(`report: ${join(config.out, 'report.json')}`);
  process.exit(report.failures.length === 0 && report.unattributedRequests.length === 0 ? 0 : 1);
}
