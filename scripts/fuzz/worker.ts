/**
 * A fuzz worker (a child process of run.ts): builds the corpora once, then runs the cases the
 * parent sends ({ kind, index }), each generated here from (seed, kind, index), and reports one
 * outcome per case. The parent enforces time and memory limits and watches for escapes.
 */
import { mkdirSync, rmSync, writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { pathToFileURL } from 'node:url';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { acquireGpuDevice } from '../../src/gpu/acquire-device.ts';
import { loadGltfScene } from '../../src/io/gltf/load-gltf-scene.ts';
import { loadSceneFile } from '../../src/io/scene-file-loader.ts';
import { loadEnvironmentMap } from '../../src/lighting/load-environment-map.ts';
import { decodeHdr } from '../../src/io/images/radiance-hdr.ts';
import { createWavefrontPathTracingComputeConfig } from '../../src/pathtracer/config.ts';
import { createWavefrontPathTracingComputeRenderer } from '../../src/pathtracer/renderer.ts';
import { prepareScene } from '../../src/pathtracer/scene/prepare-scene.ts';
import { normalizeWavefrontScene } from '../../src/scene/normalize-scene.ts';
import type { WavefrontPathTracingOptions } from '../../src/pathtracer/types.ts';
import { makeCase, type CaseKind, type Corpora, buildCorpora } from './cases.ts';
import type { LoaderCase } from './cases-gltf.ts';
import type { OptionsCase } from './cases-options.ts';
import { createWorkerSandbox, type Servers, type WorkerSandbox } from './sandbox.ts';
import type { Outcome } from './outcome.ts';

interface Init {
  type: 'init';
  runDir: string;
  worker: number;
  seed: number;
  servers: Servers;
}

let sandbox: WorkerSandbox;
let corpora: Corpora;
let init: Init;
let device: Promise<GPUDevice> | undefined;

const send = (message: unknown): void => void process.send!(message);

function describeError(error: unknown): Pick<Outcome, 'status' | 'code' | 'field' | 'message' | 'errorName' | 'cause' | 'stack'> {
  if (error instanceof GpuRendererError) {
    const cause = error.cause;
    // An internal fault caught at the boundary (a dependency dereferencing undefined, a stack
    // overflow), as opposed to a platform API refusing data by design (TextDecoder's fatal mode,
    // DataView bounds), which is how decoders are meant to report malformed input.
    const native = (cause instanceof TypeError || cause instanceof RangeError || cause instanceof ReferenceError) &&
      /Cannot read|Cannot set|is not a function|is not iterable|is not defined|is not a constructor|Maximum call stack|Invalid (typed )?array length|allocation failed|of undefined|of null/i.test(cause.message);
    return {
      status: native ? 'wrapped' : 'typed',
      code: error.code,
      field: error.field ?? '',
      message: error.message.slice(0, 300),
      ...(cause instanceof Error ? { cause: `${cause.name}: ${cause.message.slice(0, 200)}` } : {}),
      ...(native ? { stack: (cause as Error).stack?.split('\n').slice(0, 6).join('\n') } : {}),
    };
  }
  const e = error as { name?: string; message?: string; stack?: string };
  return { status: 'untyped', errorName: e?.name ?? typeof error, message: String(e?.message ?? error).slice(0, 300), stack: e?.stack?.split('\n').slice(0, 8).join('\n') };
}

/** What each renderer runs on a scene before GPU work: the scene's validation, the options' and the CPU preparation. */
async function rendererCheck(scene: object): Promise<Pick<Outcome, 'status' | 'code' | 'field' | 'message'> | undefined> {
  try {
    createWavefrontPathTracingComputeConfig({ ...(scene as object), width: 8, height: 8 } as WavefrontPathTracingOptions);
    const normalized = normalizeWavefrontScene(scene);
    // The BVH of a legal multi-million-triangle mesh is the renderer's work, not the loader's.
    if (normalized.triangleCount <= 50_000) await prepareScene(normalized, { maxTextureDimension2D: 8192, maxTextureArrayLayers: 256 });
    return undefined;
  } catch (error) {
    if (!(error instanceof GpuRendererError)) return describeError(error);
    return { status: error.code === 'SCENE_TOO_LARGE' ? 'limit' : 'late', code: error.code, field: error.field ?? '', message: error.message.slice(0, 300) };
  }
}

function writeFiles(files: Record<string, Uint8Array>): string[] {
  const written: string[] = [];
  for (const [name, bytes] of Object.entries(files)) {
    const path = join(sandbox.asset, name);
    mkdirSync(dirname(path), { recursive: true });
    writeFileSync(path, bytes);
    written.push(path);
  }
  return written;
}

async function runLoader(kind: CaseKind, c: LoaderCase): Promise<Omit<Outcome, 'kind' | 'index' | 'ms' | 'notes'>> {
  const written = writeFiles(c.files);
  const controller = new AbortController();
  if (c.abort) controller.abort();
  const options: Record<string, unknown> = { ...c.options, ...(c.abort ? { signal: controller.signal } : {}) };
  const policy = c.options.resourcePolicy as { allowedOrigins?: string[] } | null | undefined;
  const allowedOrigins = policy !== null && typeof policy === 'object' && Array.isArray(policy.allowedOrigins) ? policy.allowedOrigins : [];
  let source: unknown;
  if (c.source.kind === 'path') source = join(sandbox.asset, c.source.file);
  else if (c.source.kind === 'file-url') source = pathToFileURL(join(sandbox.asset, c.source.file));
  else if (c.source.kind === 'bytes') source = c.source.bytes;
  else source = (c.source as { value: string }).value;
  try {
    let result: object;
    if (kind === 'gltf') result = { ...(await loadGltfScene(source as string, options)) };
    else if (kind === 'scene') result = (await loadSceneFile(source as string, options)).scene;
    else {
      if (c.decoder === 'decodeHdr') decodeHdr(source as Uint8Array);
      else await loadEnvironmentMap(source as string, options);
      return { status: 'ok', allowedOrigins };
    }
    const late = await rendererCheck(result);
    return { ...(late ?? { status: 'ok' }), allowedOrigins };
  } catch (error) {
    if (c.abort && (error as Error)?.name === 'AbortError') return { status: 'aborted', allowedOrigins };
    return { ...describeError(error), allowedOrigins };
  } finally {
    for (const path of written) rmSync(path, { force: true });
  }
}

async function runOptions(c: OptionsCase): Promise<Omit<Outcome, 'kind' | 'index' | 'ms' | 'notes'>> {
  device ??= acquireGpuDevice().then((a) => a.device);
  const options = 'device' in c.options ? c.options : { ...c.options, device: await device };
  let renderer: Awaited<ReturnType<typeof createWavefrontPathTracingComputeRenderer>> | undefined;
  try {
    renderer = await createWavefrontPathTracingComputeRenderer(options as unknown as WavefrontPathTracingOptions);
    const spp = typeof options.samplesPerPixel === 'number' ? options.samplesPerPixel : 1;
    const pixels = (typeof options.width === 'number' ? options.width : 8) * (typeof options.height === 'number' ? options.height : 8);
    // Valid but expensive frames are not the point (see cases-options.ts).
    const cheap = spp <= 64 && pixels <= 65536;
    for (const call of c.calls) {
      if (call.method === 'updateCamera') renderer.updateCamera(call.argument as never);
      else if (call.method === 'readAov') await renderer.readAov(call.argument as never);
      else if (cheap) {
        const frame = call.argument as { samplesPerPixel?: unknown } | undefined;
        if (frame !== null && typeof frame === 'object' && typeof frame.samplesPerPixel === 'number' && frame.samplesPerPixel > 64) continue;
        if (call.method === 'renderFrame') await renderer.renderFrame(call.argument as never);
        else renderer.renderOnce(call.argument as never);
      }
    }
    return { status: 'ok', allowedOrigins: [] };
  } catch (error) {
    return { ...describeError(error), allowedOrigins: [] };
  } finally {
    renderer?.destroy();
  }
}

process.on('message', (message: { type: string; kind?: CaseKind; index?: number } & Partial<Init>) => {
  void (async () => {
    if (message.type === 'init') {
      init = message as Init;
      sandbox = createWorkerSandbox(init.runDir, init.worker);
      corpora = await buildCorpora();
      send({ type: 'ready' });
      return;
    }
    if (message.type !== 'case') return;
    const kind = message.kind!;
    const index = message.index!;
    const started = performance.now();
    const generated = makeCase(kind, index, init.seed, corpora, { canary: sandbox.canary, asset: sandbox.asset, servers: init.servers, caseTag: `c-${kind}-${index}`, hasFifo: sandbox.hasFifo });
    // What the case may contact, told before it runs (a case that hangs reports nothing after).
    const policy = 'options' in generated && (generated.options as Record<string, unknown>).resourcePolicy;
    const allowed = policy !== null && typeof policy === 'object' && Array.isArray((policy as { allowedOrigins?: unknown }).allowedOrigins) ? (policy as { allowedOrigins: string[] }).allowedOrigins : [];
    send({ type: 'started', kind, index, allowedOrigins: allowed });
    const result = kind === 'options' ? await runOptions(generated as OptionsCase) : await runLoader(kind, generated as LoaderCase);
    const polluted = Object.prototype.hasOwnProperty.call(Object.prototype, 'polluted');
    if (polluted) delete (Object.prototype as Record<string, unknown>).polluted;
    send({ type: 'result', outcome: { kind, index, ms: performance.now() - started, notes: generated.notes, ...result, ...(polluted ? { status: 'polluted' } : {}) } satisfies Outcome });
  })().catch((error: unknown) => {
    send({ type: 'fatal', message: String((error as Error)?.stack ?? error) });
  });
});
