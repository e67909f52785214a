/** Runs `gpu-renderer farm ...` (parsed by farm-args.ts); returns the exit code. */
import { dirname, resolve } from 'node:path';
import { defaultResourcePolicy, readByteSource } from '../io/resource-policy.ts';
import { jobKeyOf, parseJobFile } from '../farm/farm-job.ts';
import { formatFarmStatus, readFarmStatus, type FarmStatus } from '../farm/status.ts';
import { submitFarmJob } from '../farm/submit.ts';
import { runFarmWorker } from '../farm/worker.ts';
import { GpuRendererError, isGpuRendererError } from '../errors/gpu-renderer-error.ts';
import type { FarmCommand } from './commands.ts';
import type { ProgressStream } from './progress.ts';

export async function runFarmCommand(command: FarmCommand, io: { stdout: ProgressStream; stderr: ProgressStream }): Promise<number> {
  const connection = { ...(command.redis !== undefined ? { redis: command.redis } : {}), ...(command.queue !== undefined ? { queue: command.queue } : {}) };
  if (command.action === 'submit') {
    let render = command.render;
    if (command.jobFile !== undefined) {
      const path = resolve(command.jobFile);
      // Read as any input is: a regular file within the resource limits (never a pipe or device).
      const { bytes } = await readByteSource(path, defaultResourcePolicy, { code: 'INVALID_OPTION', field: 'job' });
      render = parseJobFile(new TextDecoder().decode(bytes), path, dirname(path));
    }
    const options = { ...connection, stderr: io.stderr, ...(command.name !== undefined ? { name: command.name } : {}), ...(command.attempts !== undefined ? { attempts: command.attempts } : {}), ...(command.backoffMs !== undefined ? { backoffMs: command.backoffMs } : {}) };
    const submission = await submitFarmJob(render!, options).catch((error: unknown) => {
      // A job file's errors name its keys: the asset is "scene", a flag's option its camelCase name.
      if (command.jobFile === undefined || !isGpuRendererError(error) || error.field === undefined) throw error;
      if (error.field !== 'scene' && !error.field.startsWith('--')) throw error;
      const key = error.field === 'scene' ? 'scene' : jobKeyOf(error.field);
      throw new GpuRendererError(error.code, error.message.slice(error.field.length + 2), { field: `/${key}`, cause: error });
    });
    io.stdout.write(`submitted ${submission.name}: ${submission.frames} frames, ${submission.queued} queued on ${submission.queue}${submission.existing > 0 ? `, ${submission.existing} already on disk` : ''}\n`);
    return 0;
  }
  if (command.action === 'worker') {
    const controller = new AbortController();
    const stop = (): void => controller.abort();
    process.once('SIGINT', stop);
    process.once('SIGTERM', stop);
    try {
      const trust = {
        ...(command.outputRoots !== undefined ? { outputRoots: command.outputRoots } : {}),
        ...(command.assetRoots !== undefined ? { assetRoots: command.assetRoots } : {}),
        ...(command.pathMap !== undefined ? { pathMap: command.pathMap } : {}),
        ...(command.allowedOrigins !== undefined ? { allowedOrigins: command.allowedOrigins } : {}),
      };
      const summary = await runFarmWorker({ ...connection, ...trust, exitWhenIdle: command.exitWhenIdle, log: io.stderr, signal: controller.signal, ...(command.lockDuration !== undefined ? { lockDuration: command.lockDuration } : {}), ...(command.stalledInterval !== undefined ? { stalledInterval: command.stalledInterval } : {}) });
      io.stderr.write(`worker ${summary.worker}: stopped; ${summary.written} frames written, ${summary.skipped} found done, ${summary.assetsLoaded} asset loads${summary.refused > 0 ? `, ${summary.refused} refused (see farm status)` : ''}\n`);
      return 0;
    } finally {
      process.off('SIGINT', stop);
      process.off('SIGTERM', stop);
    }
  }
  const started = Date.now();
  let status: FarmStatus;
  for (;;) {
    status = await readFarmStatus({ ...connection, ...(command.job !== undefined ? { job: command.job } : {}) });
    const settled = status.jobs.every((j) => j.remaining === 0);
    if (!command.wait || settled) break;
    if (command.timeoutSeconds !== undefined && Date.now() - started > command.timeoutSeconds * 1000) {
      io.stdout.write(`${command.json ? JSON.stringify(status) : formatFarmStatus(status)}\n`);
      io.stderr.write(`farm status: not complete after ${command.timeoutSeconds}s\n`);
      return 2;
    }
    await new Promise((r) => setTimeout(r, 500));
  }
  io.stdout.write(`${command.json ? JSON.stringify(status) : formatFarmStatus(status)}\n`);
  return 0;
}
