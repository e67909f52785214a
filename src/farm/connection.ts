/**
 * The farm's Redis: where its address comes from (`--redis`, else REDIS_URL, else the local
 * default), a reachability check with a typed error naming that source, and BullMQ loaded on
 * demand through a variable specifier (browser bundles of the package never resolve it).
 */
import type * as BullMQ from 'bullmq';
import { GpuRendererError } from '../errors/gpu-renderer-error.ts';
import { nodeModule } from '../io/platform.ts';

export const defaultRedisUrl = 'redis://127.0.0.1:6379';
export const defaultFarmQueue = 'gpu-renderer';

export interface FarmConnectionOptions {
  /**
   * redis://[user:password@]host:port[/db], or rediss://... for TLS (the server's certificate is
   * checked against Node's CAs; NODE_EXTRA_CA_CERTS adds a private CA); default REDIS_URL, else
   * redis://127.0.0.1:6379. A password never appears in messages or `farm status`.
   */
  redis?: string;
  /** The BullMQ queue's name; default 'gpu-renderer'. */
  queue?: string;
}

export interface FarmConnection {
  url: string;
  /** Where the URL came from, for errors: '--redis', 'REDIS_URL' or 'default'. */
  source: string;
  /** The URL without its password, for messages. */
  shown: string;
  queue: string;
}

/** The Redis URL and queue name, validated (INVALID_OPTION naming `--redis`, `REDIS_URL` or `--queue`). */
export function resolveFarmConnection(options: FarmConnectionOptions = {}, env: Record<string, string | undefined> = process.env): FarmConnection {
  const source = options.redis !== undefined ? '--redis' : env.REDIS_URL !== undefined && env.REDIS_URL !== '' ? 'REDIS_URL' : 'default';
  const url = options.redis ?? (source === 'REDIS_URL' ? env.REDIS_URL! : defaultRedisUrl);
  let parsed: URL;
  try {
    parsed = new URL(url);
  } catch {
    throw new GpuRendererError('INVALID_OPTION', `cannot read ${JSON.stringify(redactRedisUrl(url))} as a URL (expected redis://host:port)`, { field: source });
  }
  const shown = redactRedisUrl(url);
  if (parsed.protocol !== 'redis:' && parsed.protocol !== 'rediss:') throw new GpuRendererError('INVALID_OPTION', `expected a redis:// or rediss:// URL, got ${JSON.stringify(shown)}`, { field: source });
  if (parsed.hostname === '') throw new GpuRendererError('INVALID_OPTION', `no host in ${JSON.stringify(shown)}`, { field: source });
  const queue = options.queue ?? defaultFarmQueue;
  if (!/^[A-Za-z0-9._-]+$/.test(queue)) throw new GpuRendererError('INVALID_OPTION', `queue names are letters, digits, '.', '_' and '-', got ${JSON.stringify(queue)}`, { field: '--queue' });
  return { url, source, shown, queue };
}

export type Bull = typeof BullMQ;

let bull: Promise<Bull> | undefined;

/** BullMQ, imported on first use. */
export function loadBullmq(): Promise<Bull> {
  bull ??= nodeModule<Bull>('bullmq');
  return bull;
}

/** A minimal view of the ioredis client the farm uses for its records. */
export interface FarmRedis {
  hset(key: string, ...fieldsAndValues: (string | number)[]): Promise<number>;
  hsetnx(key: string, field: string, value: string): Promise<number>;
  hget(key: string, field: string): Promise<string | null>;
  hgetall(key: string): Promise<Record<string, string>>;
  hexists(key: string, field: string): Promise<number>;
  hlen(key: string): Promise<number>;
  hdel(key: string, ...fields: string[]): Promise<number>;
  del(...keys: string[]): Promise<number>;
  zadd(key: string, score: number, member: string): Promise<number | string>;
  zrange(key: string, start: number, stop: number): Promise<string[]>;
  ping(): Promise<string>;
  quit(): Promise<unknown>;
  disconnect(): void;
}

interface RedisConstructor {
  new (url: string, options: Record<string, unknown>): FarmRedis & { connect(): Promise<void> };
}

/**
 * A connected ioredis client, after a PING: an unreachable server is a QUEUE_UNAVAILABLE error
 * naming where the address came from, within `timeoutMs`.
 */
export async function connectRedis(connection: FarmConnection, timeoutMs = 3000): Promise<FarmRedis> {
  const module = await nodeModule<{ Redis?: RedisConstructor; default?: RedisConstructor }>('ioredis');
  const Redis = (module.Redis ?? module.default) as RedisConstructor;
  // BullMQ needs maxRetriesPerRequest null for blocking commands; the first connection fails fast instead of retrying.
  const client = new Redis(connection.url, { lazyConnect: true, connectTimeout: timeoutMs, maxRetriesPerRequest: null, retryStrategy: () => null, enableOfflineQueue: false });
  // The connection's own error (a refused password, an untrusted certificate) says more than the
  // "Connection is closed." the failed call reports after it.
  let cause: Error | undefined;
  (client as unknown as { on(event: string, listener: (error: Error) => void): void }).on('error', (error) => void (cause ??= error));
  try {
    await client.connect();
    await client.ping();
  } catch (error) {
    client.disconnect();
    const why = [cause?.message, (error as Error).message].filter((m, i, all) => m !== undefined && all.indexOf(m) === i).join('; ');
    throw new GpuRendererError('QUEUE_UNAVAILABLE', `cannot reach Redis at ${connection.shown}: ${why}`, { field: connection.source, cause: cause ?? error });
  }
  return client;
}

/** The Redis keys of the farm's own records (next to BullMQ's keys of the queue). */
export function farmKeys(queue: string, job?: string): { jobs: string; job: string; done: string; failed: string; refused: string } {
  const base = `gpu-renderer-farm:${queue}`;
  return { jobs: `${base}:jobs`, job: `${base}:job:${job ?? ''}`, done: `${base}:job:${job ?? ''}:done`, failed: `${base}:job:${job ?? ''}:failed`, refused: `${base}:refused` };
}

/** The URL as messages and `farm status` show it: a password is replaced by `***`. */
export function redactRedisUrl(url: string): string {
  try {
    const parsed = new URL(url);
    if (parsed.password === '') return url;
    parsed.password = '***';
    return parsed.href;
  } catch {
    return url;
  }
}
