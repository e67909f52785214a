/**
 * The baseline version of the path tracer benchmark: a detached git worktree of the baseline ref in
 * <temp>/gpu-renderer-bench-baseline/<checkout>-<hash>/<sha>, reused while its sha matches. It lives
 * outside the checkout because a nested checkout (its own eslint.config.js and tsconfig.json) would
 * be linted with this one and break `npm run lint`. It borrows this checkout's
 * node_modules through a symlink and falls back to its own `npm ci` when its imports do not load
 * with those; its `npm run generate` embeds its own WGSL. Every failure is returned as a reason,
 * never thrown: the bench then measures the current version only.
 */
import { spawnSync } from 'node:child_process';
import { existsSync, lstatSync, mkdirSync, realpathSync, rmSync, symlinkSync, unlinkSync } from 'node:fs';
import { createHash } from 'node:crypto';
import { tmpdir } from 'node:os';
import { basename, join } from 'node:path';
import { pathToFileURL, fileURLToPath } from 'node:url';
import { runNodeChild } from './child-protocol.ts';

export type BaselineCheckout =
  | {
    ok: true;
    ref: string;
    sha: string;
    shortSha: string;
    subject: string;
    dir: string;
    /** True when an existing worktree at the same sha was reused. */
    reused: boolean;
    /** 'symlink': this checkout's node_modules; 'own': installed there with npm ci. */
    modules: 'symlink' | 'own';
  }
  | { ok: false; ref: string; reason: string };

export interface PrepareBaselineOptions {
  /** Root of the current checkout (holds bench/ and node_modules/). */
  repoRoot: string;
  log?: (line: string) => void;
  /** Folder holding one worktree per sha; default: defaultWorktreesDir(repoRoot). */
  worktreesDir?: string;
  /** Time limit of `npm ci` in the worktree, ms. */
  installTimeoutMs?: number;
}

/** Per checkout (its real path hashed), so that each borrows its own node_modules. */
export function defaultWorktreesDir(repoRoot: string): string {
  const real = realpathSync(repoRoot);
  const key = `${basename(real)}-${createHash('sha256').update(real).digest('hex').slice(0, 10)}`;
  return join(tmpdir(), 'gpu-renderer-bench-baseline', key);
}

const CHILD_SCRIPT = fileURLToPath(new URL('./pathtracer-child.ts', import.meta.url));

interface CommandResult {
  ok: boolean;
  out: string;
  err: string;
}

function run(command: string, args: readonly string[], cwd: string, timeoutMs = 120_000): CommandResult {
  const r = spawnSync(command, [...args], { cwd, encoding: 'utf8', timeout: timeoutMs, stdio: ['ignore', 'pipe', 'pipe'] });
  const err = r.error ? `${r.error.message}\n${r.stderr ?? ''}` : (r.stderr ?? '');
  return { ok: r.status === 0 && !r.error, out: (r.stdout ?? '').trim(), err: err.trim() };
}

const git = (args: readonly string[], cwd: string): CommandResult => run('git', args, cwd);

function lastLines(text: string, n = 8): string {
  return text.split('\n').slice(-n).join('\n');
}

/** The worktree in `dir` is a checkout of its own (not a folder of the outer one) at `sha`. */
function isWorktreeAt(dir: string, sha: string): boolean {
  if (!existsSync(join(dir, '.git'))) return false;
  const top = git(['rev-parse', '--show-toplevel'], dir);
  const head = git(['rev-parse', 'HEAD'], dir);
  return top.ok && head.ok && realpathSync(top.out) === realpathSync(dir) && head.out === sha;
}

/** `npm run generate` (when the version has that script) and an import probe of its harness. */
async function generateAndProbe(dir: string): Promise<string | null> {
  const generate = run('npm', ['run', '--silent', '--if-present', 'generate'], dir);
  if (!generate.ok) return `npm run generate failed:\n${lastLines(`${generate.out}\n${generate.err}`)}`;
  const harness = join(dir, 'bench', 'pathtracer.ts');
  if (!existsSync(harness)) return 'the baseline has no bench/pathtracer.ts';
  const probe = await runNodeChild([CHILD_SCRIPT, pathToFileURL(harness).href, '--probe'], dir, 120_000);
  return probe.ok ? null : `its bench/pathtracer.ts does not load: ${probe.error}`;
}

export async function prepareBaselineCheckout(ref: string, options: PrepareBaselineOptions): Promise<BaselineCheckout> {
  const log = options.log ?? ((line: string) => console.log(line));
  const fail = (reason: string): BaselineCheckout => ({ ok: false, ref, reason });

  const top = git(['rev-parse', '--show-toplevel'], options.repoRoot);
  if (!top.ok) return fail(`${options.repoRoot} is not a git checkout, so there is no history to take the baseline from`);
  const repoRoot = top.out;

  const resolved = git(['rev-parse', '--verify', '--quiet', `${ref}^{commit}`], repoRoot);
  if (!resolved.ok) {
    const shallow = git(['rev-parse', '--is-shallow-repository'], repoRoot).out === 'true';
    return fail(
      `git ref "${ref}" is not in this repository` +
        (shallow
          ? ' (this clone is shallow: fetch the history, e.g. `git fetch --unshallow`, or `fetch-depth: 0` in CI)'
          : ' (fetch it, or name another with --baseline <ref> / BENCH_BASELINE_REF)'),
    );
  }
  const sha = resolved.out;
  const shortSha = git(['rev-parse', '--short', sha], repoRoot).out || sha.slice(0, 7);
  const subject = git(['log', '-1', '--format=%s', sha], repoRoot).out;
  const worktreesDir = options.worktreesDir ?? defaultWorktreesDir(repoRoot);
  const dir = join(worktreesDir, sha);

  let reused = false;
  if (existsSync(dir) && isWorktreeAt(dir, sha)) {
    reused = true;
    // Keep the cached checkout pristine: it must measure exactly the baseline commit.
    if (git(['status', '--porcelain', '--untracked-files=no'], dir).out !== '') {
      log(`  baseline worktree ${dir} had local changes; resetting it to ${shortSha}`);
      const reset = git(['reset', '--hard', '--quiet', sha], dir);
      if (!reset.ok) return fail(`could not reset ${dir}: ${reset.err}`);
    }
  } else {
    if (existsSync(dir)) {
      log(`  ${dir} is not a worktree at ${shortSha}; recreating it`);
      rmSync(dir, { recursive: true, force: true });
    }
    mkdirSync(worktreesDir, { recursive: true });
    git(['worktree', 'prune'], repoRoot);
    log(`  creating baseline worktree ${dir} (${shortSha})`);
    const add = git(['worktree', 'add', '--detach', '--quiet', dir, sha], repoRoot);
    if (!add.ok) return fail(`git worktree add failed: ${add.err}`);
  }

  const modulesPath = join(dir, 'node_modules');
  let modules: 'symlink' | 'own';
  const existing = existsSync(modulesPath) || (() => { try { lstatSync(modulesPath); return true; } catch { return false; } })();
  if (!existing) {
    symlinkSync(join(repoRoot, 'node_modules'), modulesPath, 'dir');
    modules = 'symlink';
  } else {
    modules = lstatSync(modulesPath).isSymbolicLink() ? 'symlink' : 'own';
  }

  let problem = await generateAndProbe(dir);
  if (problem && modules === 'symlink') {
    log(`  baseline does not load with this checkout's node_modules (${problem.split('\n')[0]}); running npm ci in ${dir}`);
    unlinkSync(modulesPath);
    const install = run('npm', ['ci', '--no-audit', '--no-fund'], dir, options.installTimeoutMs ?? 600_000);
    if (!install.ok) {
      rmSync(modulesPath, { recursive: true, force: true }); // the next run tries the symlink again
      return fail(`npm ci in ${dir} failed:\n${lastLines(install.err || install.out)}`);
    }
    modules = 'own';
    problem = await generateAndProbe(dir);
  }
  if (problem) return fail(problem);
  return { ok: true, ref, sha, shortSha, subject, dir, reused, modules };
}
