// The baseline checkout on a real throwaway git repository: a missing ref is a reason, not an
// exception; a ref becomes a detached worktree in <worktreesDir>/<sha> with its generate step run;
// when its imports do not load with the borrowed node_modules it installs its own with npm ci; a
// second run reuses it and undoes local edits.
import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { lstatSync, readdirSync, mkdirSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { defaultWorktreesDir, prepareBaselineCheckout } from '../../bench/baseline-worktree.ts';

let repo = '';
let sha = '';
let worktreesDir = '';
const quiet = (): { log: () => void; worktreesDir: string } => ({ log: () => {}, worktreesDir });
const git = (...args: string[]): string =>
  execFileSync('git', ['-c', 'user.name=bench', '-c', 'user.email=bench@example.invalid', ...args], { cwd: repo, encoding: 'utf8' }).trim();

before(() => {
  repo = mkdtempSync(join(tmpdir(), 'bench-baseline-test-'));
  worktreesDir = mkdtempSync(join(tmpdir(), 'bench-baseline-worktrees-'));
  // A local file: dependency, so that `npm ci` can install it without the network.
  mkdirSync(join(repo, 'local-dep'));
  writeFileSync(join(repo, 'local-dep', 'package.json'), JSON.stringify({ name: 'local-dep', version: '1.0.0', type: 'module', main: 'index.js' }));
  writeFileSync(join(repo, 'local-dep', 'index.js'), 'export const answer = 42;\n');
  writeFileSync(
    join(repo, 'package.json'),
    JSON.stringify({
      name: 'baseline-fixture', version: '1.0.0', private: true, type: 'module',
      scripts: { generate: 'node -e "require(\'fs\').writeFileSync(\'generated.txt\', \'ok\')"' },
      dependencies: { 'local-dep': 'file:./local-dep' },
    }),
  );
  mkdirSync(join(repo, 'bench'));
  writeFileSync(join(repo, 'bench', 'pathtracer.ts'), "import { answer } from 'local-dep';\nexport async function runPathTracerBenchmark() { return { rows: [], answer }; }\n");
  writeFileSync(join(repo, '.gitignore'), 'node_modules/\ngenerated.txt\n');
  execFileSync('npm', ['install', '--no-audit', '--no-fund', '--silent'], { cwd: repo });
  git('init', '--quiet');
  git('add', '.');
  git('commit', '--quiet', '-m', 'fixture');
  sha = git('rev-parse', 'HEAD');
  // The "current checkout" has node_modules without local-dep: the baseline must fall back to npm ci.
  rmSync(join(repo, 'node_modules'), { recursive: true });
  mkdirSync(join(repo, 'node_modules'));
});

after(() => {
  rmSync(repo, { recursive: true, force: true });
  rmSync(worktreesDir, { recursive: true, force: true });
});

test('a ref that is not in the repository is reported, not thrown', async () => {
  const r = await prepareBaselineCheckout('no-such-ref', { repoRoot: repo, ...quiet() });
  assert.equal(r.ok, false);
  assert.match(!r.ok ? r.reason : '', /"no-such-ref" is not in this repository/);
  assert.deepEqual(readdirSync(worktreesDir), []);
});

test('a folder outside git is reported, not thrown', async () => {
  const plain = mkdtempSync(join(tmpdir(), 'bench-no-git-'));
  try {
    const r = await prepareBaselineCheckout('HEAD', { repoRoot: plain, ...quiet() });
    assert.equal(r.ok, false);
  } finally {
    rmSync(plain, { recursive: true, force: true });
  }
});

test('worktree at the sha, generate run, npm ci fallback, then reuse with local edits undone', async () => {
  const first = await prepareBaselineCheckout('HEAD', { repoRoot: repo, ...quiet() });
  assert.ok(first.ok, !first.ok ? first.reason : '');
  assert.equal(first.sha, sha);
  assert.equal(first.dir, join(worktreesDir, sha));
  assert.equal(first.reused, false);
  assert.equal(execFileSync('git', ['rev-parse', 'HEAD'], { cwd: first.dir, encoding: 'utf8' }).trim(), sha);
  assert.equal(readFileSync(join(first.dir, 'generated.txt'), 'utf8'), 'ok', 'npm run generate ran in the worktree');
  assert.equal(first.modules, 'own', 'the borrowed node_modules lacks local-dep, so npm ci ran');
  assert.equal(lstatSync(join(first.dir, 'node_modules')).isSymbolicLink(), false);

  writeFileSync(join(first.dir, 'bench', 'pathtracer.ts'), 'export const broken = true;\n');
  const second = await prepareBaselineCheckout(sha.slice(0, 8), { repoRoot: repo, ...quiet() });
  assert.ok(second.ok, !second.ok ? second.reason : '');
  assert.equal(second.reused, true);
  assert.match(readFileSync(join(second.dir, 'bench', 'pathtracer.ts'), 'utf8'), /runPathTracerBenchmark/, 'local edit undone');
});

test('with a node_modules that has what it imports, the worktree borrows it through a symlink', async () => {
  rmSync(join(worktreesDir, sha), { recursive: true, force: true });
  mkdirSync(join(repo, 'node_modules', 'local-dep'), { recursive: true });
  for (const f of ['package.json', 'index.js']) writeFileSync(join(repo, 'node_modules', 'local-dep', f), readFileSync(join(repo, 'local-dep', f)));
  const r = await prepareBaselineCheckout('HEAD', { repoRoot: repo, ...quiet() });
  assert.ok(r.ok, !r.ok ? r.reason : '');
  assert.equal(r.reused, false, 'a deleted worktree folder is recreated (stale registration pruned)');
  assert.equal(r.modules, 'symlink');
  assert.ok(lstatSync(join(r.dir, 'node_modules')).isSymbolicLink());
});

test('the default worktree folder is outside the checkout and differs between checkouts', () => {
  const a = defaultWorktreesDir(repo);
  assert.ok(!a.startsWith(repo), a);
  assert.notEqual(a, defaultWorktreesDir(worktreesDir));
  assert.equal(a, defaultWorktreesDir(repo));
});
