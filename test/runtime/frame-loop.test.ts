import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createGpuRenderer } from '../../src/runtime/create-gpu-renderer.ts';
import type { RendererEncodeContext } from '../../src/runtime/renderer-types.ts';
import { getRendererWorkerManifest } from '../../src/planning/worker-manifests.ts';
import { GpuRendererError } from '../../src/errors/gpu-renderer-error.ts';
import { createShaderChecked, testDevice } from '../helpers/gpu.ts';

/** A deterministic requestAnimationFrame: the test decides when frames happen. */
function manualAnimationFrame() {
  let next = 1;
  const pending = new Map<number, (t: number) => void>();
  const cancelled: unknown[] = [];
  return {
    requestAnimationFrame: (cb: (t: number) => void) => {
      const id = next++;
      pending.set(id, cb);
      return id;
    },
    cancelAnimationFrame: (id: unknown) => {
      cancelled.push(id);
      pending.delete(id as number);
    },
    pending,
    cancelled,
    fire(timestamp: number) {
      const callbacks = [...pending.values()];
      pending.clear();
      for (const cb of callbacks) cb(timestamp);
      return callbacks.length;
    },
  };
}

function pixelAt(data: Uint8Array | Float32Array, width: number, x: number, y: number): number[] {
  const i = (y * width + x) * 4;
  return [data[i]!, data[i + 1]!, data[i + 2]!, data[i + 3]!];
}

test('renderOnce clears the offscreen target to the clear colour and exposes the pass to the host', async () => {
  const device = await testDevice();
  // The host draws a solid colour into the left half with its own pipeline, in the frame's pass.
  const module = await createShaderChecked(
    device,
    `@vertex fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4f {
       let p = array(vec2f(-1.0, -1.0), vec2f(3.0, -1.0), vec2f(-1.0, 3.0));
       return vec4f(p[i], 0.0, 1.0);
     }
     @fragment fn fs() -> @location(0) vec4f { return vec4f(1.0, 0.0, 0.0, 1.0); }`,
  );
  const pipeline = device.createRenderPipeline({
    layout: 'auto',
    vertex: { module, entryPoint: 'vs' },
    fragment: { module, entryPoint: 'fs', targets: [{ format: 'rgba8unorm' }] },
  });
  const contexts: RendererEncodeContext[] = [];
  const renderer = await createGpuRenderer({
    device,
    target: { width: 8, height: 4 },
    clearColor: '#336699',
    onBeforeEncode: (ctx) => {
      contexts.push(ctx);
      ctx.pass.setPipeline(pipeline);
      ctx.pass.setScissorRect(0, 0, ctx.size.width / 2, ctx.size.height);
      ctx.pass.draw(3);
    },
  });
  const result = await renderer.renderOnce(1234);
  assert.equal(result.frame, 1);
  assert.equal(result.timestamp, 1234);
  assert.ok(result.frameTimeMs >= 0);
  assert.equal(contexts.length, 1);
  assert.equal(contexts[0]!.format, 'rgba8unorm');
  assert.equal(contexts[0]!.device, device);
  const pixels = await renderer.readPixels();
  assert.equal(pixels.width, 8);
  assert.equal(pixels.height, 4);
  for (let y = 0; y < 4; y++) {
    for (let x = 0; x < 8; x++) {
      assert.deepEqual(pixelAt(pixels.data, 8, x, y), x < 4 ? [255, 0, 0, 255] : [0x33, 0x66, 0x99, 255], `pixel ${x},${y}`);
    }
  }
  renderer.setClearColor([0, 1, 0.5, 1]);
  await renderer.renderOnce();
  const again = await renderer.readPixels();
  assert.deepEqual(pixelAt(again.data, 8, 7, 3), [0, 255, 128, 255]);
  renderer.destroy();
});

test('premultiplied presentation premultiplies the clear colour; opaque forces alpha to 1; bgra is read back as RGBA', async () => {
  const device = await testDevice();
  const premultiplied = await createGpuRenderer({ device, target: { width: 2, height: 2 }, alpha: true, clearColor: [1, 0.5, 0, 0.5] });
  await premultiplied.renderOnce();
  const p = pixelAt((await premultiplied.readPixels()).data, 2, 1, 1);
  assert.ok(Math.abs(p[0]! - 127.5) <= 1 && Math.abs(p[1]! - 63.75) <= 1 && p[2] === 0 && Math.abs(p[3]! - 127.5) <= 1, `got ${p}`);
  premultiplied.destroy();
  const opaque = await createGpuRenderer({ device, target: { width: 2, height: 2 }, clearColor: '#10203040', format: 'bgra8unorm' });
  await opaque.renderOnce();
  assert.deepEqual(pixelAt((await opaque.readPixels()).data, 2, 0, 0), [0x10, 0x20, 0x30, 255]);
  opaque.destroy();
});

test('start() drives frames through requestAnimationFrame with hooks in order and frame ids from the factory', async () => {
  const device = await testDevice();
  const raf = manualAnimationFrame();
  const events: string[] = [];
  const completed: Promise<void>[] = [];
  let resolveComplete: (() => void) | undefined;
  const renderer = await createGpuRenderer({
    device,
    target: { width: 4, height: 4 },
    requestAnimationFrame: raf.requestAnimationFrame,
    cancelAnimationFrame: raf.cancelAnimationFrame,
    frameIdFactory: ({ frame, xrActive }) => `scene.${xrActive ? 'xr' : 'flat'}.${frame}`,
    getTargetFrameTimeMs: () => 16.7,
    onFrameStart: (info) => {
      events.push(`start:${info.frameId}`);
      completed.push(new Promise((resolve) => (resolveComplete = resolve)));
    },
    onBeforeEncode: (ctx) => events.push(`encode:${ctx.frameId}`),
    onAfterSubmit: (info) => events.push(`submit:${info.frameId}`),
    onFrameComplete: (result) => {
      events.push(`complete:${result.frameId}:${result.targetFrameTimeMs}`);
      resolveComplete?.();
    },
  });
  assert.equal(raf.pending.size, 0, 'nothing scheduled before start');
  renderer.start();
  assert.equal(renderer.getSnapshot().running, true);
  assert.equal(raf.pending.size, 1);
  raf.fire(100);
  await completed[0];
  raf.fire(116);
  await completed[1];
  assert.deepEqual(events, [
    'start:scene.flat.1',
    'encode:scene.flat.1',
    'submit:scene.flat.1',
    'complete:scene.flat.1:16.7',
    'start:scene.flat.2',
    'encode:scene.flat.2',
    'submit:scene.flat.2',
    'complete:scene.flat.2:16.7',
  ]);
  const snapshot = renderer.getSnapshot();
  assert.equal(snapshot.frame, 2);
  assert.equal(snapshot.lastFrameId, 'scene.flat.2');
  assert.equal(snapshot.lastTimestamp, 116);
  assert.equal(snapshot.profile, 'realtime');
  assert.equal(snapshot.workerManifest, getRendererWorkerManifest('realtime'));
  assert.equal(snapshot.deviceState, 'ready');
  assert.equal(raf.pending.size, 1, 'the loop keeps one frame scheduled');
  renderer.stop();
  assert.equal(renderer.getSnapshot().running, false);
  assert.equal(raf.pending.size, 0, 'stop cancels the scheduled frame');
  assert.equal(raf.fire(200), 0);
  assert.equal(renderer.getSnapshot().frame, 2);
  renderer.destroy();
});

test('a hook error in the loop stops it and reaches onError', async () => {
  const device = await testDevice();
  const raf = manualAnimationFrame();
  const errors: unknown[] = [];
  const renderer = await createGpuRenderer({
    device,
    target: { width: 2, height: 2 },
    requestAnimationFrame: raf.requestAnimationFrame,
    cancelAnimationFrame: raf.cancelAnimationFrame,
    onBeforeEncode: () => {
      throw new Error('host failure');
    },
    onError: (e) => errors.push(e),
  });
  renderer.start();
  raf.fire(1);
  assert.equal(errors.length, 1);
  assert.equal((errors[0] as Error).message, 'host failure');
  assert.equal(renderer.getSnapshot().running, false);
  assert.equal(raf.pending.size, 0);
  renderer.destroy();
});

test('resize changes the target in device pixels and validates its arguments', async () => {
  const device = await testDevice();
  const renderer = await createGpuRenderer({ device, target: { width: 3, height: 3 }, clearColor: '#ffffff' });
  renderer.resize(5, 3, 2);
  assert.deepEqual({ ...renderer.getSnapshot().size }, { width: 10, height: 6, cssWidth: 5, cssHeight: 3, devicePixelRatio: 2 });
  await renderer.renderOnce();
  const pixels = await renderer.readPixels();
  assert.equal(pixels.width, 10);
  assert.equal(pixels.height, 6);
  assert.equal(pixels.data.length, 10 * 6 * 4);
  assert.ok([...pixels.data].every((v) => v === 255));
  const isField = (field: string) => (e: unknown) => e instanceof GpuRendererError && e.code === 'INVALID_OPTION' && e.field === field;
  assert.throws(() => renderer.resize(0, 4), isField('width'));
  assert.throws(() => renderer.resize(4, Number.NaN), isField('height'));
  assert.throws(() => renderer.resize(4, 4, -1), isField('devicePixelRatio'));
  assert.throws(() => renderer.resize(device.limits.maxTextureDimension2D + 1, 4, 1), isField('width'));
  assert.equal(renderer.getSnapshot().size.width, 10, 'a rejected resize changes nothing');
  renderer.destroy();
});

test('destroy stops the loop, cancels the pending frame, destroys an owned device and rejects later use', async () => {
  const raf = manualAnimationFrame();
  let lostReason: string | undefined;
  const renderer = await createGpuRenderer({
    target: { width: 2, height: 2 },
    requestAnimationFrame: raf.requestAnimationFrame,
    cancelAnimationFrame: raf.cancelAnimationFrame,
    onDeviceLost: (info) => (lostReason = info.reason),
  });
  renderer.start();
  const handle = [...raf.pending.keys()][0];
  renderer.destroy();
  assert.deepEqual(raf.cancelled, [handle]);
  const snapshot = renderer.getSnapshot();
  assert.equal(snapshot.destroyed, true);
  assert.equal(snapshot.running, false);
  assert.equal(snapshot.deviceState, 'destroyed');
  // The renderer owned its device, so destroy() destroyed it: WebGPU resolves `lost` with "destroyed".
  const info = await renderer.device.lost;
  assert.equal(info.reason, 'destroyed');
  assert.equal(lostReason, undefined, 'an intentional destroy is not reported as a loss');
  await assert.rejects(renderer.renderOnce(), (e: unknown) => e instanceof GpuRendererError && e.code === 'RENDERER_DESTROYED');
  assert.throws(() => renderer.start(), (e: unknown) => e instanceof GpuRendererError && e.code === 'RENDERER_DESTROYED');
  renderer.destroy();
});
