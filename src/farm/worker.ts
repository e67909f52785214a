/**
 * `farm worker`: pulls frame jobs from the queue one at a time (one GPU), renders each and writes it
 * to the shared output directory atomically. Guarantees, with BullMQ's:
 * - a frame is never lost: a failed frame is retried with exponential backoff; a worker that dies
 *   mid-frame stops renewing its lock, and after `lockDuration` BullMQ's stalled-job check (every
 *   `stalledInterval`, run by every live worker) hands the frame to another worker;
 * - a frame is written once: the file is linked into place only if absent (first writer wins), a
 *   frame whose completion record or file exists is not rendered again, and the completion record
 *   is set only once (HSETNX);
 * - an asset is read once per worker: the loaded asset, its environment map and the path tracer
 *   stay cached while consecutive frames share them (the renderer is updated in place);
 * - a job is untrusted input: its data must pass the frame schema (frame-data-schema.ts) and its
 *   paths must lie inside the worker's roots (worker-trust.ts), or the frame fails at once, without
 *   retries, with FARM_JOB_REFUSED recorded for `farm status`; nothing is read or written outside
 *   the roots, and only the worker's own allowed origins are fetched from.
 */
import { hostname } from 'node:os';
import type * as BullMQ from 'bullmq';
import { isReachRefusal, type ResourcePolicy } from '../io/resource-policy.ts';
import type { ProgressStream } from '../cli/progress.ts';
import { accumulateImage, encodeOutput, loadGltfForCommand, rendererSettings } from '../cli/render-command.ts';
import { applyCameraFlags } from '../cli/camera-flags.ts';
import { applyCliLighting } from '../cli/scene-lighting.ts';
import type { WavefrontCameraInput } from '../scene/types.ts';
import type { GltfScene } from '../io/gltf/gltf-scene-reader.ts';
import { frameFileExists, writeFrameFile } from '../io/frame-files.ts';
import { poseGltfSequenceItem } from '../sequence/gltf-sequence.ts';
import { createSequenceRenderer, type SequenceRenderer } from '../sequence/sequence-renderer.ts';
import { GpuRendererError, isGpuRendererError } from '../errors/gpu-renderer-error.ts';
import { connectRedis, farmKeys, loadBullmq, resolveFarmConnection, type FarmConnectionOptions } from './connection.ts';
import type { FarmFrameData } from './farm-job.ts';
import { failureOf, recordFrameFailure, recordMalformedJob } from './failure-record.ts';
import { frameJobOf, validateFrameData } from './frame-data-schema.ts';
import { confineFrame, prepareOutputFolder, resolveFarmTrust, type FarmTrustOptions } from './worker-trust.ts';

/**
 * A worker's options. `outputRoots` and `assetRoots` (or their environment variables) are
 * required: without them the worker does not start (INVALID_OPTION naming --output-root / --asset-root).
 */
export interface FarmWorkerOptions extends FarmConnectionOptions, FarmTrustOptions {
  /** How long a frame's lock holds without renewal (ms); a dead worker's frame is taken over after it. Default 30000. */
  lockDuration?: number;
  /** How often this worker checks for stalled frames (ms); default 15000. */
  stalledInterval?: number;
  /** Exit once the queue has nothing waiting, delayed or active (a Kubernetes Job's workers). */
  exitWhenIdle?: boolean;
  /** One line per frame and per asset loaded. */
  log?: ProgressStream;
  /** Stops the worker (it finishes the frame in hand). */
  signal?: AbortSignal;
}

export interface FarmWorkerSummary {
  worker: string;
  /** Frames this worker rendered and wrote. */
  written: number;
  /** Frames it found done already (a record or a file) and left alone. */
  skipped: number;
  /** Assets it loaded (one per asset and settings, however many frames). */
  assetsLoaded: number;
  /** Frames it refused (FARM_JOB_REFUSED: outside its roots or origins, or breaking the schema). */
  refused: number;
}

interface CachedAsset {
  key: string;
  gltf: GltfScene;
  /** The camera --orbit / --camera-position place, for every frame. */
  placed: WavefrontCameraInput | undefined;
  sequence: SequenceRenderer;
}

function positiveMs(value: number | undefined, fallback: number, field: string): number {
  const ms = value ?? fallback;
  if (!Number.isFinite(ms) || ms <= 0) throw new GpuRendererError('INVALID_OPTION', `expected milliseconds > 0, got ${ms}`, { field });
  return ms;
}

export async function runFarmWorker(options: FarmWorkerOptions = {}): Promise<FarmWorkerSummary> {
  const connection = resolveFarmConnection(options);
  // Before anything else: a worker without roots does not start.
  const trust = await resolveFarmTrust(options);
  const lockDuration = positiveMs(options.lockDuration, 30000, '--lock-duration');
  const stalledInterval = positiveMs(options.stalledInterval, 15000, '--stalled-interval');
  const redis = await connectRedis(connection);
  const { Worker, Queue, UnrecoverableError } = await loadBullmq();
  const id = `${hostname()}:${process.pid}`;
  const log = (line: string): void => void options.log?.write(`worker ${id}: ${line}\n`);
  const summary: FarmWorkerSummary = { worker: id, written: 0, skipped: 0, assetsLoaded: 0, refused: 0 };
  let cached: CachedAsset | null = null;

  const assetFor = async (render: FarmFrameData['render'], scenePolicy: ResourcePolicy, envPolicy: ResourcePolicy): Promise<CachedAsset> => {
    const settings = rendererSettings(render);
    const key = JSON.stringify([render.scenePath, render.camera, render.variant, render.animation, render.at, render.env, render.envIntensity, render.envRotationDegrees, render.negativeTexels, render.orbit, render.cameraPosition, render.cameraTarget, render.fovYDegrees, settings]);
    if (cached?.key === key) return cached;
    cached?.sequence.destroy();
    cached = null;
    // Every read goes through the policy: the scene's references (buffers, images), after symbolic
    // links, stay inside the asset root holding the scene; the environment map inside its own.
    const gltf = await loadGltfForCommand(render.scenePath!, { camera: render.camera, variant: render.variant, animation: render.animation, at: render.at, aspectRatio: render.width / render.height, resourcePolicy: scenePolicy, ...(options.log ? { stderr: options.log } : {}) });
    const { scene: lit, lighting } = await applyCliLighting({ ...gltf }, render, (text) => log(`note: ${text}`), envPolicy);
    const environment = lit.environmentMap !== undefined ? { environmentMap: lit.environmentMap } : {};
    const placed = render.orbit !== undefined || render.cameraPosition !== undefined ? applyCameraFlags({ ...gltf }, render).camera : undefined;
    summary.assetsLoaded += 1;
    log(`loaded ${render.scenePath}; ${lighting}`);
    cached = { key, gltf, placed, sequence: createSequenceRenderer({ ...settings, ...environment }) };
    return cached;
  };

  /** A refused job fails once (no retries: the same data is refused again), its reason recorded for `farm status`. */
  const refuse = async (job: BullMQ.Job, error: unknown): Promise<never> => {
    const failure = failureOf(error, id);
    summary.refused += 1;
    const owner = frameJobOf(job.data);
    if (owner !== undefined) await recordFrameFailure(redis, connection.queue, owner.job, owner.index, failure);
    else await recordMalformedJob(redis, connection.queue, job.id ?? job.name, failure);
    log(`${owner !== undefined ? `${owner.job} #${owner.index}` : `queue job ${job.id}`} refused: ${failure.message}`);
    throw new UnrecoverableError(`${failure.code ?? 'FARM_JOB_REFUSED'}: ${failure.message}`);
  };

  const renderFrame = async (job: BullMQ.Job<FarmFrameData>): Promise<string> => {
    let confined: Awaited<ReturnType<typeof confineFrame>>;
    try {
      confined = await confineFrame(validateFrameData(job.data), trust);
    } catch (error) {
      if (isGpuRendererError(error) && error.code === 'FARM_JOB_REFUSED') return refuse(job, error);
      throw error;
    }
    const { job: name, index, path, item, render } = confined.data;
    const keys = farmKeys(connection.queue, name);
    const record = (extra: Record<string, unknown>): Promise<number> => redis.hsetnx(keys.done, String(index), JSON.stringify({ path, worker: id, at: new Date().toISOString(), ...extra }));
    if ((await redis.hexists(keys.done, String(index))) === 1) {
      summary.skipped += 1;
      return 'done already';
    }
    if (!render.overwrite && (await frameFileExists(path))) {
      await record({ existing: true });
      summary.skipped += 1;
      return 'file exists';
    }
    log(`frame ${item.frame} (${name} #${index}) started`);
    const started = performance.now();
    let asset: CachedAsset;
    try {
      asset = await assetFor(render, confined.scenePolicy, confined.envPolicy);
    } catch (error) {
      // A reference the resource policy refuses (outside the asset root, an origin not allowed) is a refusal too.
      if (isReachRefusal(error)) return refuse(job, new GpuRendererError('FARM_JOB_REFUSED', `the asset's references reach outside the worker's asset roots or allowed origins: ${(error as Error).message}`, { field: 'render.scenePath', cause: error }));
      throw error;
    }
    let bytes: Uint8Array;
    try {
      const frame = await poseGltfSequenceItem(asset.gltf, item);
      const renderer = await asset.sequence.show(asset.placed !== undefined ? { ...frame.options, camera: asset.placed } : applyCameraFlags(frame.options, { ...render, orbit: undefined, cameraPosition: undefined }));
      await accumulateImage(renderer, render, () => undefined);
      bytes = await encodeOutput(renderer, render);
    } catch (error) {
      // A renderer that failed (a lost device) is not reused: the next frame starts afresh.
      asset.sequence.destroy();
      cached = null;
      throw error;
    }
    try {
      await prepareOutputFolder(path, trust);
    } catch (error) {
      if (isGpuRendererError(error) && error.code === 'FARM_JOB_REFUSED') return refuse(job, error);
      throw error;
    }
    const written = await writeFrameFile(path, bytes, render.overwrite ? 'replace' : 'create');
    const seconds = (performance.now() - started) / 1000;
    await record({ seconds, written });
    if (written) {
      summary.written += 1;
      log(`frame ${item.frame} (${name} #${index}) wrote ${path} in ${seconds.toFixed(2)}s`);
    } else {
      summary.skipped += 1;
      log(`frame ${item.frame} (${name} #${index}) was written by another worker meanwhile; kept theirs`);
    }
    return written ? 'written' : 'written by another worker';
  };

  const worker = new Worker<FarmFrameData>(connection.queue, renderFrame, {
    connection: { url: connection.url, maxRetriesPerRequest: null },
    concurrency: 1,
    lockDuration,
    stalledInterval,
    maxStalledCount: 3,
    name: id,
  });
  worker.on('failed', (job, error) => {
    // Refusals were recorded where they were found; the data of such a job is not to be read here.
    if (job === undefined || error instanceof UnrecoverableError) return;
    const owner = frameJobOf(job.data);
    if (owner === undefined) return;
    const attempts = job.opts.attempts ?? 1;
    const frame = (job.data as Partial<FarmFrameData>).item?.frame;
    log(`frame ${frame} (${owner.job} #${owner.index}) failed (try ${job.attemptsMade} of ${attempts}): ${error.message}`);
    if (job.attemptsMade >= attempts) void recordFrameFailure(redis, connection.queue, owner.job, owner.index, failureOf(error, id));
  });
  worker.on('error', (error) => log(`error: ${error.message}`));

  await new Promise<void>((resolve) => {
    let idleChecks = 0;
    const queue = options.exitWhenIdle ? new Queue(connection.queue, { connection: { url: connection.url } }) : null;
    const stop = (): void => {
      clearInterval(timer);
      void Promise.all([worker.close(), queue?.close()]).then(() => resolve(), () => resolve());
    };
    const timer = setInterval(() => {
      if (options.signal?.aborted) return stop();
      if (queue === null) return;
      void queue.getJobCounts('wait', 'active', 'delayed', 'prioritized', 'waiting-children').then((counts) => {
        const open = Object.values(counts).reduce((a, b) => a + b, 0);
        idleChecks = open === 0 ? idleChecks + 1 : 0;
        if (idleChecks >= 2) stop();
      });
    }, 500);
    options.signal?.addEventListener('abort', stop, { once: true });
  });
  (cached as CachedAsset | null)?.sequence.destroy();
  await redis.quit();
  return summary;
}
