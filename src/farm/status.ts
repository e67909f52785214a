/** `farm status`: every job's progress from the farm's completion records, and the queue's counts. */
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { connectRedis, farmKeys, loadBullmq, resolveFarmConnection, type FarmConnectionOptions } from './connection.ts';
import { formatFailure, readFrameFailures, readMalformedJobs, type FrameFailure } from './failure-record.ts';

export interface FarmJobStatus {
  name: string;
  scene: string;
  out: string;
  frames: number;
  /** Frames with a completion record (rendered, or found on disk). */
  done: number;
  /** Frames that failed every try, or that a worker refused. */
  failed: number;
  /** Why they failed (FARM_JOB_REFUSED: a worker would not run the frame; `field` names the job's field). */
  failures: FrameFailure[];
  /** Frames neither done nor failed. */
  remaining: number;
  /** Every frame done. */
  complete: boolean;
  submittedAt: string;
}

export interface FarmStatus {
  queue: string;
  redis: string;
  /** BullMQ's counts over the whole queue. */
  counts: { waiting: number; active: number; delayed: number; completed: number; failed: number };
  /** Workers connected to the queue now. */
  workers: number;
  jobs: FarmJobStatus[];
  /** Queue jobs a worker refused whose data names no valid farm job. */
  malformed: FrameFailure[];
}

export async function readFarmStatus(options: FarmConnectionOptions & { job?: string } = {}): Promise<FarmStatus> {
  const connection = resolveFarmConnection(options);
  const redis = await connectRedis(connection);
  const { Queue } = await loadBullmq();
  const queue = new Queue(connection.queue, { connection: { url: connection.url } });
  try {
    const keys = farmKeys(connection.queue);
    const names = options.job !== undefined ? [options.job] : await redis.zrange(keys.jobs, 0, -1);
    const jobs: FarmJobStatus[] = [];
    for (const name of names) {
      const k = farmKeys(connection.queue, name);
      const record = await redis.hgetall(k.job);
      if (record.name === undefined) throw new GpuRendererError('INVALID_OPTION', `no farm job ${JSON.stringify(name)} in queue ${connection.queue}`, { field: 'job' });
      const frames = Number(record.frames);
      const done = await redis.hlen(k.done);
      const failures = await readFrameFailures(redis, connection.queue, name);
      const failed = failures.length;
      jobs.push({ name, scene: record.scene ?? '', out: record.out ?? '', frames, done, failed, failures, remaining: Math.max(0, frames - done - failed), complete: done >= frames, submittedAt: record.submittedAt ?? '' });
    }
    const c = await queue.getJobCounts('wait', 'active', 'delayed', 'completed', 'failed', 'prioritized');
    const workers = (await queue.getWorkers()).length;
    return {
      queue: connection.queue,
      redis: connection.shown,
      counts: { waiting: (c.wait ?? 0) + (c.prioritized ?? 0), active: c.active ?? 0, delayed: c.delayed ?? 0, completed: c.completed ?? 0, failed: c.failed ?? 0 },
      workers,
      jobs,
      malformed: options.job !== undefined ? [] : await readMalformedJobs(redis, connection.queue),
    };
  } finally {
    await queue.close();
    await redis.quit();
  }
}

export function formatFarmStatus(s: FarmStatus): string {
  const lines = s.jobs.map((j) => {
    const state = j.complete ? 'complete' : j.failed > 0 && j.remaining === 0 ? `${j.failed} failed` : `${j.remaining} to go${j.failed > 0 ? `, ${j.failed} failed` : ''}`;
    const head = `${j.name}: ${j.done}/${j.frames} frames done (${((100 * j.done) / Math.max(1, j.frames)).toFixed(0)}%), ${state} -> ${j.out}`;
    // The reasons, a few per job (a job refused frame by frame would otherwise fill the screen).
    const shown = j.failures.slice(0, 5).map((f) => `  ${formatFailure(f)}`);
    if (j.failures.length > shown.length) shown.push(`  ... and ${j.failures.length - shown.length} more (--json lists them all)`);
    return [head, ...shown].join('\n');
  });
  for (const f of s.malformed.slice(0, 5)) lines.push(`refused ${formatFailure(f)}`);
  if (lines.length === 0) lines.push('no jobs');
  const c = s.counts;
  lines.push(`queue ${s.queue} at ${s.redis}: ${c.waiting} waiting, ${c.active} active, ${c.delayed} delayed (retry backoff), ${c.completed} completed, ${c.failed} failed; ${s.workers} worker${s.workers === 1 ? '' : 's'} connected`);
  return lines.join('\n');
}
