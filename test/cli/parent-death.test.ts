// The CLI renders in a child process (main.ts, to filter Dawn's notices). Killing the CLI with
// SIGKILL gives it no chance to stop that child, so the child watches for its parent's death
// (parent-watch.ts): it must be gone within 2 s, during a long render.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawn, type ChildProcess } from 'node:child_process';
import { mkdtemp, readdir, readFile, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';

const cli = fileURLToPath(new URL('../../src/cli/main.ts', import.meta.url));

/** /proc/<pid>/stat's state and parent pid, or undefined once the process is gone. */
async function procStat(pid: number): Promise<{ state: string; ppid: number } | undefined> {
  try {
    // The command name (field 2) is in parentheses and may hold spaces: read after its last ')'.
    const stat = await readFile(`/proc/${pid}/stat`, 'utf8');
    const [state, ppid] = stat.slice(stat.lastIndexOf(')') + 2).split(' ');
    return { state: state!, ppid: Number(ppid) };
  } catch {
    return undefined;
  }
}

/** Whether `pid` still runs: signal 0 reaches it, and it is no zombie waiting for a reaper (pid 1 in a container may never reap). */
async function running(pid: number): Promise<boolean> {
  try {
    process.kill(pid, 0);
  } catch {
    return false;
  }
  return (await procStat(pid))?.state !== 'Z';
}

async function childrenOf(pid: number): Promise<number[]> {
  const pids = (await readdir('/proc')).filter((name) => /^\d+$/.test(name)).map(Number);
  const children: number[] = [];
  for (const candidate of pids) if ((await procStat(candidate))?.ppid === pid) children.push(candidate);
  return children;
}

async function until<T>(what: string, timeoutMs: number, probe: () => Promise<T | undefined>): Promise<T> {
  const deadline = Date.now() + timeoutMs;
  for (;;) {
    const value = await probe();
    if (value !== undefined) return value;
    if (Date.now() > deadline) assert.fail(`timed out after ${timeoutMs} ms waiting for ${what}`);
    await new Promise((r) => setTimeout(r, 50));
  }
}

/**
 * Starts `parent`, finds its child with `findChild` and lets it run `settleMs`, then kills the
 * parent with SIGKILL and requires the child gone within 2 s; kills whatever is left either way.
 */
async function killParentOf(parent: ChildProcess, findChild: () => Promise<number | undefined>, settleMs: number): Promise<void> {
  // 'exit', not 'close': the child may hold the parent's pipes open.
  const parentExited = new Promise((resolve) => parent.on('exit', resolve));
  let child: number | undefined;
  try {
    child = await until('the child to start', 20_000, findChild);
    await new Promise((r) => setTimeout(r, settleMs));
    assert.ok(await running(child), 'the child ended on its own');
    parent.kill('SIGKILL');
    await parentExited;
    const killed = Date.now();
    await until('the child to end after its parent', 2000, async () => ((await running(child!)) ? undefined : true));
    const took = Date.now() - killed;
    assert.ok(took <= 2000, `the child took ${took} ms`);
  } finally {
    parent.kill('SIGKILL');
    if (child !== undefined && (await running(child))) process.kill(child, 'SIGKILL');
  }
}

const linuxOnly = { skip: process.platform !== 'linux' && 'reads /proc' };

test('kill -9 of the CLI ends its rendering child within 2 s', linuxOnly, async () => {
  const dir = await mkdtemp(join(tmpdir(), 'gpu-renderer-parent-death-'));
  try {
    // A render that would run for many minutes on any device.
    const parent = spawn(process.execPath, [cli, 'render', '--width', '64', '--height', '64', '--spp', '1048576', '--spp-per-frame', '1', '--out', join(dir, 'x.png')], { stdio: ['ignore', 'ignore', 'ignore'] });
    // The child gets 3 s into its work (loading modules, opening the device, compiling) before its parent dies.
    await killParentOf(parent, async () => (await childrenOf(parent.pid!))[0], 3000);
  } finally {
    await rm(dir, { recursive: true, force: true });
  }
});

test('the watch ends a child whose main thread is blocked, spawned without an IPC channel', linuxOnly, async () => {
  const watch = fileURLToPath(new URL('../../src/cli/parent-watch.ts', import.meta.url));
  // The child busy-waits for up to a minute: only the watcher's thread can end it sooner.
  const childScript = `import { watchParent } from ${JSON.stringify(watch)}; watchParent(() => process.exit(1)); console.log(process.pid); const end = Date.now() + 60000; while (Date.now() < end);`;
  const parentScript = `require('node:child_process').spawn(process.execPath, ['--input-type=module', '-e', ${JSON.stringify(childScript)}], { stdio: ['ignore', 'inherit', 'inherit'] }); setInterval(() => {}, 1000);`;
  const parent = spawn(process.execPath, ['-e', parentScript], { stdio: ['ignore', 'pipe', 'inherit'] });
  let stdout = '';
  parent.stdout.setEncoding('utf8').on('data', (text: string) => (stdout += text));
  await killParentOf(parent, async () => (/^\d+\n/.test(stdout) ? Number(stdout.trim()) : undefined), 500);
});
