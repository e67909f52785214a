import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createGpuRenderer } from '../../src/runtime/create-gpu-renderer.ts';
import { parseClearColor } from '../../src/runtime/clear-color.ts';
import { createRendererDebugHooks, type RendererDebugFrameSample } from '../../src/runtime/debug-hooks.ts';
import { acquireGpuDevice } from '../../src/gpu/acquire-device.ts';
import { supportsWebGpu } from '../../src/gpu/supports-webgpu.ts';
import { GpuRendererError, type GpuRendererErrorCode } from '../../src/errors/gpu-renderer-error.ts';
import { testDevice } from '../helpers/gpu.ts';

const typed = (code: GpuRendererErrorCode, field: string) => (e: unknown) => e instanceof GpuRendererError && e.code === code && e.field === field;

test('clear colours parse from hex and arrays', () => {
  assert.deepEqual([...parseClearColor('#102035')], [0x10 / 255, 0x20 / 255, 0x35 / 255, 1]);
  assert.deepEqual([...parseClearColor('#FF000080')], [1, 0, 0, 0x80 / 255]);
  assert.deepEqual([...parseClearColor([0.1, 0.2, 0.3, 0.4])], [0.1, 0.2, 0.3, 0.4]);
});

test('invalid options are typed errors naming the field, before any GPU work', async () => {
  const cases: [Record<string, unknown>, GpuRendererErrorCode, string][] = [
    [{ clearColor: '#12345' }, 'INVALID_OPTION', 'clearColor'],
    [{ clearColor: 'red' }, 'INVALID_OPTION', 'clearColor'],
    [{ clearColor: [1, 2, 0, 1] }, 'INVALID_OPTION', 'clearColor[1]'],
    [{ clearColor: [1, 0, 0] }, 'INVALID_OPTION', 'clearColor'],
    [{ format: 'rgb8' }, 'INVALID_OPTION', 'format'],
    [{ powerPreference: 'fast' }, 'INVALID_OPTION', 'powerPreference'],
    [{ alpha: 'yes' }, 'INVALID_OPTION', 'alpha'],
    [{ device: {} }, 'INVALID_OPTION', 'device'],
    [{ onFrameStart: 3 }, 'INVALID_OPTION', 'onFrameStart'],
    [{ frameIdFactory: 'x' }, 'INVALID_OPTION', 'frameIdFactory'],
    [{ requestAnimationFrame: {} }, 'INVALID_OPTION', 'requestAnimationFrame'],
    [{ cancelAnimationFrame: () => undefined }, 'INVALID_OPTION', 'requestAnimationFrame'],
    [{ target: { width: 0, height: 2 } }, 'INVALID_OPTION', 'target.width'],
    [{ target: { width: 2, height: 1.5 } }, 'INVALID_OPTION', 'target.height'],
    [{ canvas: 42 }, 'INVALID_CANVAS', 'canvas'],
    [{ canvas: '#scene' }, 'INVALID_CANVAS', 'canvas'],
    [{ canvas: {} }, 'INVALID_CANVAS', 'canvas'],
  ];
  for (const [options, code, field] of cases) {
    await assert.rejects(createGpuRenderer(options as never), typed(code, field), JSON.stringify(options));
  }
  await assert.rejects(createGpuRenderer('nope' as never), typed('INVALID_OPTION', 'options'));
  const device = await testDevice();
  const renderer = await createGpuRenderer({ device, target: { width: 1, height: 1 }, frameIdFactory: () => '' });
  await assert.rejects(renderer.renderOnce(), typed('INVALID_OPTION', 'frameIdFactory'));
  assert.throws(() => renderer.setClearColor('#xyzxyz'), typed('INVALID_OPTION', 'clearColor'));
  renderer.destroy();
  assert.equal(device.lost instanceof Promise, true);
});

test('supportsWebGpu reports the Dawn adapter', async () => {
  assert.equal(await supportsWebGpu(), true);
  assert.equal(await supportsWebGpu({ requireAdapter: false }), true);
});

test('device loss is reported by callback and snapshot; a new renderer replaces the lost one', async () => {
  const { device } = await acquireGpuDevice();
  let onLost: (info: { reason: string; message: string }) => void = () => undefined;
  const lost = new Promise<{ reason: string; message: string }>((resolve) => (onLost = resolve));
  const renderer = await createGpuRenderer({ device, target: { width: 2, height: 2 }, clearColor: '#ff0000', onDeviceLost: onLost });
  await renderer.renderOnce();
  renderer.start();
  // A real loss: the shared device is destroyed behind the renderer's back.
  device.destroy();
  const info = await lost;
  assert.equal(info.reason, 'destroyed');
  const snapshot = renderer.getSnapshot();
  assert.equal(snapshot.deviceState, 'lost');
  assert.equal(snapshot.deviceLost?.reason, 'destroyed');
  assert.equal(snapshot.running, false, 'the loop stops on loss');
  await assert.rejects(renderer.renderOnce(), (e: unknown) => e instanceof GpuRendererError && e.code === 'DEVICE_LOST');
  await assert.rejects(renderer.readPixels(), (e: unknown) => e instanceof GpuRendererError && e.code === 'DEVICE_LOST');
  renderer.destroy();

  const replacement = await createGpuRenderer({ target: { width: 2, height: 2 }, clearColor: '#00ff00' });
  assert.notEqual(replacement.device, device);
  await replacement.renderOnce();
  assert.deepEqual([...(await replacement.readPixels()).data.slice(0, 4)], [0, 255, 0, 255]);
  assert.equal(replacement.getSnapshot().deviceState, 'ready');
  replacement.destroy();
});

test('debug hooks record every completed frame with its id, frame time and negotiated target', async () => {
  const device = await testDevice();
  const samples: RendererDebugFrameSample[] = [];
  let target = 16.6;
  const hooks = createRendererDebugHooks({ debugSession: { recordFrame: (s) => samples.push(s) }, getTargetFrameTimeMs: () => target });
  const renderer = await createGpuRenderer({
    device,
    target: { width: 1, height: 1 },
    frameIdFactory: ({ frame, xrActive }) => `scene.${xrActive ? 'xr' : 'flat'}.${frame}`,
    ...hooks,
  });
  const first = await renderer.renderOnce();
  target = 11.1;
  const second = await renderer.renderOnce();
  assert.deepEqual(samples, [
    { frameId: 'scene.flat.1', frameTimeMs: first.frameTimeMs, targetFrameTimeMs: 16.6 },
    { frameId: 'scene.flat.2', frameTimeMs: second.frameTimeMs, targetFrameTimeMs: 11.1 },
  ]);
  assert.ok(samples.every((s) => s.frameTimeMs >= 0 && Number.isFinite(s.frameTimeMs)));
  renderer.destroy();

  const governed = createRendererDebugHooks({ debugSession: { recordFrame: () => undefined }, governor: { getSnapshot: () => ({ targetFrameTimeMs: 8.3 }) } });
  assert.equal(governed.getTargetFrameTimeMs(), 8.3);
  assert.throws(() => createRendererDebugHooks({ debugSession: {} as never }), typed('INVALID_OPTION', 'debugSession'));
  assert.throws(() => createRendererDebugHooks({ debugSession: { recordFrame: () => undefined }, governor: 1 as never }), typed('INVALID_OPTION', 'governor'));
});
