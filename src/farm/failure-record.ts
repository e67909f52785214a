/**
 * Why a frame failed, as `farm status` shows it: a record per failed frame in its job's `failed`
 * hash (the error's code, field and message, the worker, the time). A frame whose data is too
 * malformed to name its job is recorded against its queue job id in the queue's `refused` hash.
 */
import { isGpuRendererError } from '../errors/gpu-renderer-error.ts';
import { farmKeys, type FarmRedis } from './connection.ts';

export interface FrameFailure {
  /** The frame's index in its job (for a malformed job: undefined, see `queueJob`). */
  index?: number;
  /** The BullMQ job id, for a frame whose data names no valid job. */
  queueJob?: string;
  /** The typed error's code (FARM_JOB_REFUSED for a job the worker will not run). */
  code?: string;
  /** The job's field at fault. */
  field?: string;
  message: string;
  worker?: string;
  at?: string;
}

/** Longest message kept (a record must stay small whatever the job said). */
const MAX_MESSAGE = 2000;

/** The record of `error`, as stored. */
export function failureOf(error: unknown, worker: string): Omit<FrameFailure, 'index' | 'queueJob'> {
  const message = (error instanceof Error ? error.message : String(error)).slice(0, MAX_MESSAGE);
  return {
    ...(isGpuRendererError(error) ? { code: error.code, ...(error.field !== undefined ? { field: error.field } : {}) } : {}),
    message,
    worker,
    at: new Date().toISOString(),
  };
}

/** Records frame `index` of job `job` as failed with `failure`. */
export async function recordFrameFailure(redis: FarmRedis, queue: string, job: string, index: number, failure: Omit<FrameFailure, 'index' | 'queueJob'>): Promise<void> {
  await redis.hset(farmKeys(queue, job).failed, String(index), JSON.stringify(failure));
}

/** Records a queue job whose data names no valid farm job. */
export async function recordMalformedJob(redis: FarmRedis, queue: string, queueJob: string, failure: Omit<FrameFailure, 'index' | 'queueJob'>): Promise<void> {
  await redis.hset(farmKeys(queue).refused, queueJob.slice(0, 200), JSON.stringify(failure));
}

function parse(value: string): Omit<FrameFailure, 'index' | 'queueJob'> {
  try {
    const record = JSON.parse(value) as unknown;
    if (typeof record === 'object' && record !== null && typeof (record as FrameFailure).message === 'string') return record as FrameFailure;
  } catch {
    // An older record: the message alone.
  }
  return { message: value };
}

/** The failure records of a job's frames, by index. */
export async function readFrameFailures(redis: FarmRedis, queue: string, job: string): Promise<FrameFailure[]> {
  const records = await redis.hgetall(farmKeys(queue, job).failed);
  return Object.entries(records).map(([index, value]) => ({ index: Number(index), ...parse(value) })).sort((a, b) => a.index! - b.index!);
}

/** The queue's malformed jobs. */
export async function readMalformedJobs(redis: FarmRedis, queue: string): Promise<FrameFailure[]> {
  const records = await redis.hgetall(farmKeys(queue).refused);
  return Object.entries(records).map(([queueJob, value]) => ({ queueJob, ...parse(value) }));
}

/** One line for a failure: `#3 FARM_JOB_REFUSED at path: ...`. */
export function formatFailure(failure: FrameFailure): string {
  const what = failure.index !== undefined ? `#${failure.index}` : `queue job ${failure.queueJob}`;
  const message = failure.field !== undefined && failure.message.startsWith(`${failure.field}: `) ? failure.message.slice(failure.field.length + 2) : failure.message;
  return `${what} ${failure.code ?? 'failed'}${failure.field !== undefined ? ` at ${failure.field}` : ''}: ${message}`;
}
