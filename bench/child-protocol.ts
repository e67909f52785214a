/**
 * How the bench parent runs a child Node process and reads its result: the child prints one line
 * `RESULT_PREFIX + JSON`; stdout and stderr are kept for the error message when it fails.
 */
import { spawn } from 'node:child_process';

export const RESULT_PREFIX = '@@gpu-renderer-bench-result ';

export type ChildOutcome =
  | { ok: true; value: unknown; seconds: number }
  | { ok: false; error: string; seconds: number };

function tail(text: string, lines: number): string {
  return text.trimEnd().split('\n').slice(-lines).join('\n');
}

/** Runs `node <args>` in `cwd` with the parent's Node binary and environment. Never rejects. */
export function runNodeChild(args: readonly string[], cwd: string, timeoutMs: number): Promise<ChildOutcome> {
  const started = performance.now();
  const seconds = (): number => (performance.now() - started) / 1000;
  return new Promise((resolve) => {
    const child = spawn(process.execPath, [...args], { cwd, env: process.env, stdio: ['ignore', 'pipe', 'pipe'], timeout: timeoutMs, killSignal: 'SIGKILL' });
    let stdout = '';
    let stderr = '';
    child.stdout.setEncoding('utf8').on('data', (chunk: string) => { stdout += chunk; });
    child.stderr.setEncoding('utf8').on('data', (chunk: string) => { stderr += chunk; });
    child.on('error', (error) => resolve({ ok: false, error: `could not start node: ${error.message}`, seconds: seconds() }));
    child.on('close', (code, signal) => {
      const line = stdout.split('\n').reverse().find((l) => l.startsWith(RESULT_PREFIX));
      if (code === 0 && line !== undefined) {
        try {
          resolve({ ok: true, value: JSON.parse(line.slice(RESULT_PREFIX.length)) as unknown, seconds: seconds() });
          return;
        } catch (error) {
          resolve({ ok: false, error: `unreadable result line: ${(error as Error).message}`, seconds: seconds() });
          return;
        }
      }
      const why = signal ? `killed by ${signal}${signal === 'SIGKILL' ? ` (time limit ${Math.round(timeoutMs / 1000)} s?)` : ''}` : `exit code ${code}`;
      const output = tail(`${stdout}\n${stderr}`, 15);
      resolve({ ok: false, error: `${why}${line === undefined ? ', no result line' : ''}\n${output}`, seconds: seconds() });
    });
  });
}
