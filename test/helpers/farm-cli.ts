// The farm CLI in-process for tests: `farm(args)` runs `gpu-renderer farm ...` with captured
// output; `rejectsWith` asserts a typed error's code, field and message.
import assert from 'node:assert/strict';
import { parseCliArgs } from '../../src/cli/args.ts';
import type { FarmCommand } from '../../src/cli/commands.ts';
import { runFarmCommand } from '../../src/cli/farm-command.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';

export function capture(): { write(text: string): boolean; text: string } {
  return { text: '', write(text: string) { this.text += text; return true; } };
}

export async function farm(args: string[]): Promise<{ code: number; stdout: string; stderr: string }> {
  const stdout = capture();
  const stderr = capture();
  const code = await runFarmCommand(parseCliArgs(['farm', ...args]) as FarmCommand, { stdout, stderr });
  return { code, stdout: stdout.text, stderr: stderr.text };
}

export async function rejectsWith(promise: Promise<unknown>, code: string, field: string, message?: RegExp): Promise<void> {
  await assert.rejects(promise, (e: unknown) => {
    assert.ok(e instanceof GpuRendererError, String(e));
    assert.equal(e.code, code, e.message);
    assert.equal(e.field, field, e.message);
    if (message) assert.match(e.message, message);
    return true;
  });
}
