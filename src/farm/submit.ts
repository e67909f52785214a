/**
 * `farm submit`: plans the job's sequence on this machine (loading the asset once validates it and
 * fixes the turntable framing, the variant and camera lists), records the job in Redis and enqueues
 * one BullMQ job per frame with a deterministic id (`<job>.<index>`), so submitting the same job
 * again adds nothing twice and retries the frames that had failed every try. Frames whose file
 * exists are recorded as done, not enqueued (unless --overwrite, which also clears the job's old
 * completion records).
 */
import { createHash } from 'node:crypto';
import { basename } from 'node:path';
import type { RenderCommand } from '../cli/args.ts';
import type { ProgressStream } from '../cli/progress.ts';
import { commandResourcePolicy, loadGltfForCommand } from '../cli/render-command.ts';
import { planCommandSequence } from '../cli/sequence-command.ts';
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { frameFileExists } from '../io/frame-files.ts';
import { connectRedis, farmKeys, loadBullmq, resolveFarmConnection, type FarmConnectionOptions } from './connection.ts';
import { farmRenderCommand, frameRenderSettings, type FarmFrameData } from './farm-job.ts';
import { validateFrameData } from './frame-data-schema.ts';

export interface FarmSubmitOptions extends FarmConnectionOptions {
  /** The job's name (letters, digits, '.', '_', '-'); default the asset's name and a hash of the job. */
  name?: string;
  /** Tries per frame before it counts as failed; default 3. */
  attempts?: number;
  /** First retry delay in ms, doubling per retry; default 5000. */
  backoffMs?: number;
  /** Where warnings go. */
  stderr?: ProgressStream;
}

export interface FarmSubmission {
  name: string;
  queue: string;
  /** Frames in the job. */
  frames: number;
  /** Frames enqueued now. */
  queued: number;
  /** Frames whose file existed, recorded as done. */
  existing: number;
}

/** Frames enqueued per BullMQ addBulk call. */
const BULK = 500;

function jobName(command: RenderCommand, paths: readonly string[]): string {
  const hash = createHash('sha256').update(JSON.stringify({ command: frameRenderSettings(command), paths })).digest('hex').slice(0, 10);
  const base = basename(command.scenePath!).replace(/\.(glb|gltf)$/i, '').replace(/[^A-Za-z0-9._-]/g, '_');
  return `${base}-${hash}`;
}

export async function submitFarmJob(input: RenderCommand, options: FarmSubmitOptions = {}): Promise<FarmSubmission> {
  const connection = resolveFarmConnection(options);
  const command = farmRenderCommand(input);
  if (options.name !== undefined && !/^[A-Za-z0-9._-]+$/.test(options.name)) throw new GpuRendererError('INVALID_OPTION', `job names are letters, digits, '.', '_' and '-', got ${JSON.stringify(options.name)}`, { field: '--name' });
  const attempts = options.attempts ?? 3;
  const backoffMs = options.backoffMs ?? 5000;
  if (!(await frameFileExists(command.scenePath!))) throw new GpuRendererError('INVALID_OPTION', `no asset at ${command.scenePath}`, { field: 'scene' });
  // Planned here as a worker will load it: no network origins (they are the workers' own).
  const gltf = await loadGltfForCommand(command.scenePath!, { camera: command.camera, variant: command.variant, animation: command.animation, at: command.at, aspectRatio: command.width / command.height, resourcePolicy: commandResourcePolicy(command), ...(options.stderr ? { stderr: options.stderr } : {}) });
  const { items, paths } = planCommandSequence(gltf, command);
  const name = options.name ?? jobName(command, paths);
  const render = frameRenderSettings(command);
  const redis = await connectRedis(connection);
  const { Queue } = await loadBullmq();
  const queue = new Queue(connection.queue, { connection: { url: connection.url } });
  try {
    const keys = farmKeys(connection.queue, name);
    if (command.overwrite) await redis.del(keys.done, keys.failed);
    await redis.hset(keys.job, 'name', name, 'scene', command.scenePath!, 'out', command.out, 'frames', items.length, 'submittedAt', new Date().toISOString(), 'attempts', attempts);
    await redis.zadd(keys.jobs, Date.now(), name);
    const queued: { name: string; data: FarmFrameData; opts: Record<string, unknown> }[] = [];
    let existing = 0;
    const round = Date.now();
    for (let i = 0; i < items.length; i++) {
      if (!command.overwrite && (await frameFileExists(paths[i]!))) {
        await redis.hsetnx(keys.done, String(i), JSON.stringify({ path: paths[i], worker: 'submit', existing: true, at: new Date().toISOString() }));
        existing++;
        continue;
      }
      // Workers validate every job's data; checking it here gives the same errors before anything is queued.
      const data = validateFrameData(JSON.parse(JSON.stringify({ job: name, index: i, path: paths[i]!, item: items[i]!, render })) as unknown);
      queued.push({
        name: 'frame',
        data,
        // BullMQ ignores a job whose id exists: resubmitting enqueues nothing twice (--overwrite: a new round of ids).
        opts: { jobId: command.overwrite ? `${name}.${i}.r${round}` : `${name}.${i}`, attempts, backoff: { type: 'exponential', delay: backoffMs }, removeOnComplete: false, removeOnFail: false },
      });
    }
    for (let i = 0; i < queued.length; i += BULK) await queue.addBulk(queued.slice(i, i + BULK));
    // Frames that failed every try in an earlier submission: their queue jobs still exist (so the
    // adds above were ignored); retry them.
    for (const index of Object.keys(await redis.hgetall(keys.failed))) {
      const job = await queue.getJob(`${name}.${index}`);
      if (job !== undefined && (await job.isFailed())) await job.retry();
      await redis.hdel(keys.failed, index);
    }
    return { name, queue: connection.queue, frames: items.length, queued: queued.length, existing };
  } finally {
    await queue.close();
    await redis.quit();
  }
}
